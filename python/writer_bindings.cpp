// The writers (per-patch CSV and .vtp, Matrix Market F) and the Matrix Market reader, as the CLI's outputs.
#include "apps/distinct_files.h"
#include <pybind11/stl/filesystem.h>

#include <cctype>

#include "bindings.h"
#include "core/error.h"
#include "formfactor/form_factor_file.h"
#include "formfactor/matrix_market.h"
#include "interruptible.h"
#include "io/cell_field.h"
#include "io/csv_writer.h"
#include "io/vtp_writer.h"

namespace radwalk::python {
namespace {

// Refuses an output that is one of the scene's input files (the scene, its material libraries), as the CLI does.
void check_not_an_input(const std::string& path, const Scene& scene) {
  std::vector<app::NamedFile> inputs = {{"the scene", scene.path}};
  for (const Material& m : scene.patches.materials)
    if (!m.file.empty()) inputs.push_back({"the scene's material library", m.file});
  const std::string clash = app::check_distinct_files({{"the output", path}}, inputs);
  if (!clash.empty()) throw InputError(clash);
}

// Refuses a field or metadata name the .vtp (and a CSV header) cannot hold: one ParaView accepts as an identifier
// (io/cell_field.h: letters, digits and underscores, not starting with a digit, not a reserved word). The
// message escapes control characters (printable), as every message does.
void check_field_name(const std::string& name, const char* what) {
  if (name.empty() || paraview_name(name) != name || is_calculator_reserved(name) ||
      std::isdigit(static_cast<unsigned char>(name[0])))
    throw InputError(std::string(what) + " '" + printable(name) +
                     "' is not a name ParaView's Calculator accepts (letters, digits and '_', not starting with a "
                     "digit, not a reserved word such as var)");
}

// A CSV column name: no control character, comma or quote (the header is one line of plain names).
void check_csv_name(const std::string& name) {
  for (const char c : name)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f || c == ',' || c == '"')
      throw InputError("CSV name '" + printable(name) +
                       "' holds a control character, a comma or a quote, which a CSV header cannot hold");
  if (name.empty()) throw InputError("a CSV name must not be empty");
}

// dict name -> array (N,) or (N, 3), or -> (array, csv_name): CellFields in the dict's order. Integer arrays are
// counts (FieldKind::count: Int64 in the .vtp), floating ones quantities.
// Names are checked for the file they go to: `vtp` ParaView identifiers (check_field_name), else CSV names.
std::vector<CellField> cell_fields(const py::dict& fields, std::size_t n, bool vtp) {
  std::vector<CellField> out;
  const py::module_ np = py::module_::import("numpy");
  for (const auto& [key, value] : fields) {
    CellField f;
    if (!py::isinstance<py::str>(key)) throw InputError("field names must be str");
    f.name = key.cast<std::string>();
    if (vtp)
      check_field_name(f.name, "field name");
    else
      check_csv_name(f.name);
    py::object array = py::reinterpret_borrow<py::object>(value);
    if (py::isinstance<py::tuple>(array)) {
      const py::tuple t = array.cast<py::tuple>();
      if (t.size() != 2) throw InputError("field '" + f.name + "': expected an array or (array, csv_name)");
      array = t[0];
      if (!py::isinstance<py::str>(t[1])) throw InputError("field '" + f.name + "': csv_name must be str");
      f.csv_name = t[1].cast<std::string>();
      check_csv_name(f.csv_name);
    }
    array = real_array(array, "field '" + f.name + "': not an array of numbers",
                       "field '" + f.name + "': values must be real numbers, not");
    if (np.attr("issubdtype")(array.attr("dtype"), np.attr("integer")).cast<bool>()) f.kind = FieldKind::count;
    const auto a = array.cast<DoubleArray>();
    const bool rgb = a.ndim() == 2 && a.shape(1) == 3;
    if (!(a.ndim() == 1 || rgb) || static_cast<std::size_t>(a.shape(0)) != n)
      throw InputError("field '" + f.name + "': expected shape (" + std::to_string(n) + ",) or (" +
                       std::to_string(n) + ", 3), one row per patch");
    f.components = rgb ? 3 : 1;
    f.values.assign(a.data(), a.data() + a.size());
    out.push_back(std::move(f));
  }
  return out;
}

// An int metadata value as int64 (a Python int beyond it is refused, not wrapped).
std::int64_t integer_value(const std::string& name, const py::handle& value) {
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
  if (overflow != 0) throw InputError("metadata '" + name + "': the integer does not fit in 64 bits");
  return v;
}

void write_csv(const std::filesystem::path& file, const Scene& scene, const py::dict& fields) {
  const std::string path = file.string();
  check_not_an_input(path, scene);
  const std::vector<CellField> f = cell_fields(fields, scene.patches.size(), false);
  py::gil_scoped_release release;
  write_patch_csv(path, scene.patches, f);
}

void write_vtp(const std::filesystem::path& file, const Scene& scene, const py::dict& fields, const py::dict& metadata) {
  const std::string path = file.string();
  check_not_an_input(path, scene);
  std::vector<CellField> all = patch_fields(scene.patches);
  for (CellField& f : cell_fields(fields, scene.patches.size(), true)) all.push_back(std::move(f));
  VtpMetadata m;
  for (const auto& [key, value] : metadata) {
    if (!py::isinstance<py::str>(key)) throw InputError("metadata names must be str");
    const std::string k = key.cast<std::string>();
    check_field_name(k, "metadata name");
    if (py::isinstance<py::bool_>(value) || py::isinstance<py::int_>(value))
      m.set_integer(k, integer_value(k, value));
    else if (py::isinstance<py::float_>(value))
      m.set_real(k, value.cast<double>());
    else
      m.set_text(k, py::str(value).cast<std::string>());
  }
  py::gil_scoped_release release;
  write_vtp(path, scene.patches, all, m);
}

}  // namespace

void bind_writers(py::module_& m) {
  m.def("write_csv", &write_csv, py::arg("path"), py::arg("scene"), py::arg("fields") = py::dict(),
        R"doc(Writes the per-patch CSV of the CLI (io/csv_writer.h), atomically.

Columns patch,face,area,cx,cy,cz,nx,ny,nz,rho_r,rho_g,rho_b,E_r,E_g,E_b,object,group,material (the scene as it is now,
edits included; the names as the scene file gives them),
then each field of `fields` in its order: name -> (N,) array (one column) or (N, 3) array (NAME_r, NAME_g,
NAME_b) of real numbers (any real dtype, written as float64; integer dtypes as counts), or name -> (array,
csv_name) for a different CSV name. Lengths in mesh units, rho dimensionless, E in W per unit length squared. 12 significant digits, empty cells for non-finite
values. The CLI's solve CSV is write_csv(path, scene, {**ff.diagnostics, **result.fields}), byte for byte.
Refuses (InputError) to write over the scene or its MTL. path "-" writes to standard output (file descriptor 1,
not sys.stdout), as the CLI's --csv -.)doc");
  m.def("write_vtp", &write_vtp, py::arg("path"), py::arg("scene"), py::arg("fields") = py::dict(),
        py::arg("metadata") = py::dict(),
        R"doc(Writes a .vtp for ParaView (io/vtp_writer.h): the patch fields (patch, face, area, normal, rho, E), then
`fields` (as write_csv; integer arrays become Int64 count arrays; the names must be ParaView identifiers, e.g.
B_var, not var), and `metadata` (dict str -> str/int/float) as field data. A field B, (N, 3) in W per unit
length squared, is written as B (N,) the channel mean, B_rgb (N, 3) and its true-colour B_srgb (N, 3) uint8.)doc");
  m.def(
      "write_matrix_market",
      [](const std::filesystem::path& file, const py::object& F, const Scene& scene) {
        const std::string path = file.string();
        check_not_an_input(path, scene);
        std::map<std::string, double> timings;
        const SparseF f = form_factor_matrix(F, scene, 1000, 1, 0, timings);
        py::gil_scoped_release release;
        write_matrix_market(path, f);
      },
      py::arg("path"), py::arg("F"), py::arg("scene"),
      "Writes F (a FormFactors, or a scipy.sparse (N, N) matrix or array, converted to float32) as the CLI's Matrix "
      "Market file (`formfactors -o F.mtx`), coordinate real general, 1-based, atomically; byte for byte the CLI's "
      "for the same F.");
  m.def(
      "read_form_factors",
      [](const std::filesystem::path& path, const Scene& scene) {
        FormFactorsResult r;
        r.area = scene.patches.area;
        r.ff.F = interruptible([&] { return radwalk::read_form_factors(path.string(), scene.patches.size()); });
        return r;
      },
      py::arg("path"), py::arg("scene"),
      "Reads F for the scene as the CLI's --form-factors does, its format chosen by the extension (.npz: binary "
      "CSR as scipy.sparse.save_npz(..., compressed=False) writes it; anything else: Matrix Market): a FormFactors "
      "without ray counts (F an (N, N) float32 csr_matrix). InputError with the CLI's message for a malformed file "
      "or a size that is not (N, N).");
}

}  // namespace radwalk::python
