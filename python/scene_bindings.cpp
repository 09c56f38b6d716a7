// radwalk.load and the Scene type: the PatchSet of a validated, patched scene, with numpy views of its arrays.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <utility>

#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "core/error.h"
#include "interruptible.h"
#include "mesh/material_override.h"
#include "mesh/mesh_from_arrays.h"
#include "mesh/prepare_mesh.h"
#include "mesh/read_scene.h"
#include "mesh/validate.h"
#include "patch/patch_scene.h"
#include "solve/response_spec.h"

namespace radwalk::python {
namespace {

// target[...] = values (numpy broadcasting), for `scene.rho = values`.
void assign(py::object target, py::object values) { py::module_::import("numpy").attr("copyto")(target, values); }

// Scene.groups and Scene.group_names: the mesh's groups that hold a patch (an OBJ `o desk` directly followed by
// `g top` declares the object alone too, a group without faces), renumbered in order, each named as the user named
// it: "object/group", or the one of the two the file gives.
void keep_used_groups(const Mesh& mesh, Scene& scene) {
  std::vector<std::int32_t> renumbered(mesh.groups.size(), -1);
  for (std::int32_t g : scene.group)
    if (g >= 0) renumbered[static_cast<std::size_t>(g)] = 0;
  for (std::size_t g = 0; g < mesh.groups.size(); ++g) {
    if (renumbered[g] < 0) continue;
    renumbered[g] = static_cast<std::int32_t>(scene.groups.size());
    scene.groups.push_back(mesh.groups[g]);
    const std::string object = g < mesh.group_object.size() ? mesh.group_object[g] : "";
    const std::string name = g < mesh.group_name.size() ? mesh.group_name[g] : "";
    scene.group_names.push_back(object.empty() ? name : name.empty() ? object : object + "/" + name);
  }
  for (std::int32_t& g : scene.group)
    if (g >= 0) g = renumbered[static_cast<std::size_t>(g)];
}

// The Scene of a mesh: validated and patched as every CLI command does (validate_mesh, then patch_scene: the CLI's
// load_patches without its notes); its repairs and notices are one UserWarning that counts them (the lines are in
// Scene.warnings).
// `preparation` is the CLI's scaling, material overrides and validation options (mesh/prepare_mesh.h).
// The patches, contact regions, groups and warnings of a patched mesh, into `scene` (its patches and regions moved
// out; its mesh left as it is).
void take_patched(PatchedScene& patched, Scene& scene) {
  scene.patches = std::move(patched.patches);
  scene.contact_regions = std::move(patched.contact_regions);
  scene.group = patch_groups(patched.mesh, scene.patches);  // through the input face of every (repaired) face
  keep_used_groups(patched.mesh, scene);
  scene.warnings = patched.mesh.warnings;
  scene.notes = validation_notes(patched.mesh.findings, 10);
  scene.cut = patched.cut;
}

Scene patched_scene(std::function<Mesh()> read, const std::string& path, double max_edge, double max_area,
                    const MeshPreparation& preparation, bool two_sided, bool contact_cut) {
  Scene scene;
  const bool strict = preparation.tolerances.strict;
  interruptible([&] {
    Mesh mesh = read();
    prepare_mesh(mesh, preparation);
    ScenePatchingOptions patching;
    patching.split.max_edge = max_edge;
    patching.split.max_area = max_area;
    patching.contact_cut = contact_cut;
    patching.two_sided = two_sided;
    PatchedScene patched = patch_scene(std::move(mesh), patching);
    // Kept faces with contacts: the mesh (not cut, since nothing was split) for a later split's cut.
    const bool cut_later = contact_cut && !patched.cut && !patched.contacts.empty();
    take_patched(patched, scene);
    if (cut_later) scene.uncut_mesh = std::make_shared<const Mesh>(std::move(patched.mesh));
  });
  scene.path = path;
  scene.max_edge = max_edge;
  scene.max_area = max_area;
  scene.strict = strict;
  scene.orient = orient_mode_name(preparation.tolerances.orient);
  scene.open_shells = open_shell_sides_name(preparation.tolerances.open_shells);
  scene.two_sided = two_sided;
  scene.contact_cut = contact_cut;
  if (!scene.warnings.empty()) {
    const std::string summary = path + ": " + std::to_string(scene.warnings.size()) +
                                (scene.warnings.size() == 1 ? " repair or notice" : " repairs or notices") +
                                " (Scene.warnings lists them): " + scene.warnings.front() +
                                (scene.warnings.size() > 1 ? " ..." : "");
    PyErr_WarnEx(PyExc_UserWarning, summary.c_str(), 1);
  }
  return scene;
}

// Reads, validates and patches a scene file (read_scene, then patched_scene with the CLI's reading options: the
// same parsers and order as --orient, --open-shells, --scale, --unit, --set and --rho-scale).
Scene load(const std::filesystem::path& file, double max_edge, double max_area, bool strict, bool two_sided,
           bool contact_cut, const py::object& orient, const std::string& open_shells, double scale,
           const py::object& unit, const py::object& set, double rho_scale) {
  const std::string path = file.string();
  MeshPreparation preparation;
  preparation.tolerances.strict = strict;
  // None: the default (outward; a file of radwalk's patches as written keeps its run's orientation), as --orient
  // left out; a name: that orientation, as --orient NAME given.
  if (!orient.is_none() && !py::isinstance<py::str>(orient))
    throw InputError("orient must be a str (outward, consistent, none) or None");
  preparation.tolerances.orient_given = !orient.is_none();
  preparation.tolerances.orient = parse_orient_mode(orient.is_none() ? "outward" : orient.cast<std::string>());
  preparation.tolerances.open_shells = parse_open_shell_sides(open_shells);
  if (!unit.is_none() && !py::isinstance<py::str>(unit)) throw InputError("unit must be a str (mm, cm, m, in, ft) or None");
  const LengthUnit length = checked_length_unit(unit.is_none() ? std::string() : unit.cast<std::string>(), scale);
  preparation.scale = scale;
  if (!(std::isfinite(rho_scale) && rho_scale >= 0)) throw InputError("rho_scale must be a finite number >= 0");
  preparation.rho_scale = rho_scale;
  if (!set.is_none()) {
    // One "NAME.Kd=r,g,b" string or a list of them, each parsed as --set parses it.
    if (py::isinstance<py::str>(set)) {
      preparation.overrides.push_back(parse_material_override(set.cast<std::string>()));
    } else {
      for (const py::handle item : py::iter(set)) {
        if (!py::isinstance<py::str>(item))
          throw InputError("set: each override is a str 'NAME.Kd=r,g,b' or 'NAME.Ke=r,g,b', as the CLI's --set");
        preparation.overrides.push_back(parse_material_override(item.cast<std::string>()));
      }
    }
  }
  Scene scene = patched_scene(
      [&] {
        if (!std::filesystem::exists(path)) throw InputError(path + ": no such file");
        ReadOptions read;
        read.strict = strict;
        return read_scene(path, read);
      },
      path, max_edge, max_area, preparation, two_sided, contact_cut);
  scene.scale = scale;
  scene.unit = length.file_unit;
  scene.length_unit = length.length();
  scene.radiosity_unit = length.radiosity();
  return scene;
}

// A float64 array of shape (rows, columns) from any array-like (a (rows,) array or a number is repeated over the
// columns when `broadcast`); InputError naming `what` otherwise. Non-finite values are left to validation.
std::vector<double> float_rows(const py::object& value, std::size_t rows, std::size_t columns, const char* what,
                               bool broadcast) {
  const DoubleArray a = double_array(value, std::string(what) + " must be an array of numbers",
                                     std::string(what) + " must hold real numbers, not");
  std::vector<double> out(rows * columns);
  const double* d = a.data();
  if (broadcast && a.ndim() == 0) {
    std::fill(out.begin(), out.end(), d[0]);
  } else if (broadcast && a.ndim() == 1 && static_cast<std::size_t>(a.shape(0)) == rows) {
    for (std::size_t r = 0; r < rows; ++r)
      for (std::size_t c = 0; c < columns; ++c) out[r * columns + c] = d[r];
  } else if (a.ndim() == 2 && static_cast<std::size_t>(a.shape(0)) == rows &&
             static_cast<std::size_t>(a.shape(1)) == columns) {
    std::copy(d, d + rows * columns, out.begin());
  } else {
    throw InputError(std::string(what) + " has shape " + shape_text(a) + "; expected (" + std::to_string(rows) + ", " +
                     std::to_string(columns) + ")" + (broadcast ? " or (" + std::to_string(rows) + ",)" : ""));
  }
  return out;
}

// The faces argument: an (F, k) integer array (k >= 3) or a sequence of sequences of vertex indices.
std::vector<std::vector<std::int64_t>> face_lists(const py::object& faces) {
  const py::module_ np = py::module_::import("numpy");
  std::vector<std::vector<std::int64_t>> out;
  const auto integer_list = [&](const py::handle& row) {
    const py::array a = np.attr("asarray")(row);
    if (a.ndim() != 1) throw InputError("faces: a face must be a list of vertex indices");
    if (a.size() == 0) return std::vector<std::int64_t>{};
    const std::string kind = py::str(a.dtype().attr("kind"));
    if (kind != "i" && kind != "u")
      throw InputError("faces: vertex indices must be integers, got dtype " + std::string(py::str(a.dtype())));
    if (kind == "u" && a.itemsize() == 8 &&
        np.attr("max")(a).cast<unsigned long long>() > static_cast<unsigned long long>(
                                                           std::numeric_limits<std::int64_t>::max()))
      throw InputError("faces: a vertex index does not fit in 64 bits");
    const auto v = a.attr("astype")("int64").cast<py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>>();
    return std::vector<std::int64_t>(v.data(), v.data() + v.size());
  };
  if (py::isinstance<py::array>(faces) && py::array(faces).ndim() == 2) {
    const py::array a(faces);
    for (py::ssize_t f = 0; f < a.shape(0); ++f) out.push_back(integer_list(a.attr("__getitem__")(f)));
    return out;
  }
  try {
    for (const py::handle row : py::iter(faces)) out.push_back(integer_list(row));
  } catch (const py::error_already_set& e) {
    if (!e.matches(PyExc_TypeError) && !e.matches(PyExc_ValueError)) throw;
    throw InputError("faces must be an (F, 3) or (F, 4) integer array or a list of lists of vertex indices");
  }
  return out;
}

}  // namespace

Scene cut_for_splitting(const Scene& scene) {
  if (!scene.uncut_mesh) throw InternalError("cut_for_splitting: the scene keeps no uncut mesh");
  Scene out = scene;  // the uncut scene's patches are its input faces: a small copy, overwritten below
  out.uncut_mesh = nullptr;
  interruptible([&] {
    ScenePatchingOptions patching;
    patching.contact_cut = true;
    patching.splits_later = true;
    patching.two_sided = scene.two_sided;
    out.groups.clear();
    out.group_names.clear();
    PatchedScene patched = patch_scene(Mesh(*scene.uncut_mesh), patching);
    take_patched(patched, out);
  });
  // rho and E as the Scene holds them (edited in place or by set_material): every piece takes its input face's
  // values (pieces keep their input face and side), which are one per face and side.
  const PatchSet& from = scene.patches;
  PatchSet& to = out.patches;
  std::map<std::pair<std::int32_t, int>, std::size_t> patch_of;
  for (std::size_t i = 0; i < from.size(); ++i) {
    const auto key = std::make_pair(from.face[i], static_cast<int>(from.side_of(i)));
    const auto [it, added] = patch_of.emplace(key, i);
    if (!added && ((from.rho[i] != from.rho[it->second]).any() || (from.E[i] != from.E[it->second]).any()))
      throw InputError(scene.path + ": input face " + std::to_string(from.face[i]) +
                       " has patches with different rho or E, which its pieces cut along the contacts cannot "
                       "inherit: load the scene with max_edge or max_area (cut as it loads) or contact_cut=False");
  }
  for (std::size_t i = 0; i < to.size(); ++i) {
    const auto it = patch_of.find(std::make_pair(to.face[i], static_cast<int>(to.side_of(i))));
    if (it == patch_of.end())
      throw InternalError("cut_for_splitting: a piece of input face " + std::to_string(to.face[i]) +
                          " has no patch in the uncut scene");
    to.rho[i] = from.rho[it->second];
    to.E[i] = from.E[it->second];
  }
  to.materials = from.materials;
  return out;
}

Scene scene_from_arrays(const py::object& vertices, const py::object& faces, const py::object& rho,
                        const py::object& emission, const py::object& groups, bool two_sided, double max_edge,
                        double max_area, bool strict, bool contact_cut, const std::string& name) {
  FaceArrays arrays;
  const py::module_ np = py::module_::import("numpy");
  const py::array v = np.attr("asarray")(vertices, py::arg("dtype") = np.attr("float64"));
  if (v.ndim() != 2 || v.shape(1) != 3) throw InputError("vertices must be a (V, 3) array of coordinates");
  const std::vector<double> xyz = float_rows(vertices, static_cast<std::size_t>(v.shape(0)), 3, "vertices", false);
  for (std::size_t k = 0; k + 2 < xyz.size(); k += 3) arrays.vertices.emplace_back(xyz[k], xyz[k + 1], xyz[k + 2]);
  arrays.faces = face_lists(faces);
  const std::size_t n = arrays.faces.size();
  const std::vector<double> r = float_rows(rho, n, 3, "rho", true);
  for (std::size_t f = 0; f < n; ++f) arrays.rho.emplace_back(r[3 * f], r[3 * f + 1], r[3 * f + 2]);
  if (!emission.is_none()) {
    const std::vector<double> e = float_rows(emission, n, 3, "emission", true);
    for (std::size_t f = 0; f < n; ++f) arrays.emission.emplace_back(e[3 * f], e[3 * f + 1], e[3 * f + 2]);
  }
  if (!groups.is_none()) {
    for (const py::handle g : py::iter(groups)) {
      if (!py::isinstance<py::str>(g)) throw InputError("groups: one name (str) per face");
      arrays.group.push_back(g.cast<std::string>());
    }
  }
  MeshPreparation preparation;
  preparation.tolerances.strict = strict;
  return patched_scene([&] { ReadOptions read; read.strict = strict; return mesh_from_arrays(arrays, name, read); },
                       name, max_edge, max_area, preparation, two_sided, contact_cut);
}

namespace {

// Scene.from_arrays (scene_from_arrays, named "<arrays>").
Scene from_arrays(const py::object& vertices, const py::object& faces, const py::object& rho,
                  const py::object& emission, const py::object& groups, bool two_sided, double max_edge,
                  double max_area, bool strict, bool contact_cut) {
  return scene_from_arrays(vertices, faces, rho, emission, groups, two_sided, max_edge, max_area, strict, contact_cut,
                           "<arrays>");
}

std::size_t material_index(const Scene& scene, const py::object& material) {
  const auto& materials = scene.patches.materials;
  if (py::isinstance<py::str>(material)) {
    const std::string name = material.cast<std::string>();
    for (std::size_t k = 0; k < materials.size(); ++k)
      if (materials[k].name == name) return k;
    throw InputError("unknown material '" + name + "' (the scene's materials are listed in Scene.materials)");
  }
  if (!py::isinstance<py::int_>(material) || py::isinstance<py::bool_>(material))
    throw InputError("a material is named by its name (str) or its index (int) into Scene.materials");
  int overflow = 0;
  const long long k = PyLong_AsLongLongAndOverflow(material.ptr(), &overflow);
  if (overflow != 0)
    throw InputError("material index " + py::str(material).cast<std::string>() + " is outside [0, " +
                     std::to_string(materials.size()) + ")");
  if (k < 0 || static_cast<std::size_t>(k) >= materials.size())
    throw InputError("material index " + std::to_string(k) + " is outside [0, " + std::to_string(materials.size()) +
                     ")");
  return static_cast<std::size_t>(k);
}

// An RGB argument of set_material: a number (the same in every channel) or 3 numbers; None: not given.
std::optional<Rgb> rgb_argument(const py::object& value, const char* name) {
  if (value.is_none()) return std::nullopt;
  const std::string must = std::string(name) + " must be a number or 3 numbers (r, g, b)";
  const DoubleArray v = double_array(value, must, must + ", not");
  if (v.ndim() == 0) return Rgb::Constant(v.data()[0]);
  if (v.ndim() == 1 && v.shape(0) == 3) return Rgb(v.data()[0], v.data()[1], v.data()[2]);
  throw InputError(std::string(name) + " must be a number or 3 numbers (r, g, b), got " + std::to_string(v.size()) +
                   " numbers");
}

// Sets Kd and/or Ke of a material after checking them as validate_mesh checks an MTL's (rho in [0, 1), Ke finite,
// >= 0 and at most kMaxKe), then derives every patch's rho and E again.
void set_material(Scene& s, const py::object& material, const py::object& rho_value, const py::object& Ke_value) {
  Material& mat = s.patches.materials[material_index(s, material)];
  const std::optional<Rgb> rho = rgb_argument(rho_value, "rho"), Ke = rgb_argument(Ke_value, "Ke");
  const std::string at = "material '" + printable(mat.name) + "': ";
  if (rho)
    for (int c = 0; c < 3; ++c)
      if (!((*rho)[c] >= 0 && (*rho)[c] < 1))
        throw InputError(at + "rho = " + number_text((*rho)[c]) + " in channel " + std::to_string(c) +
                         " is outside [0, 1) (Kd)");
  if (Ke)
    for (int c = 0; c < 3; ++c)
      if (!((*Ke)[c] >= 0 && (*Ke)[c] <= kMaxKe))
        throw InputError(at + "Ke = " + number_text((*Ke)[c]) + " in channel " + std::to_string(c) +
                         " must be finite, >= 0 and at most " + number_text(kMaxKe));
  if (rho) mat.Kd = *rho;
  if (Ke) mat.Ke = *Ke;
  set_radiometry_from_materials(s.patches);
}

}  // namespace

void bind_scene(py::module_& m) {
  py::class_<Material>(m, "Material", "A material of the scene, as read from its MTL (or PLY colours).")
      .def_readonly("name", &Material::name, "The material's name (str), as in the MTL's newmtl.")
      .def_property_readonly("Kd", [](const Material& x) { return std::vector<double>(x.Kd.begin(), x.Kd.end()); },
                             "Diffuse reflectance rho = Kd, a list of 3 floats (r, g, b), each in [0, 1).")
      .def_property_readonly("Ke", [](const Material& x) { return std::vector<double>(x.Ke.begin(), x.Ke.end()); },
                             "Emitted radiance L_e = Ke, a list of 3 floats (r, g, b) in W per unit length squared per sr; "
                             "the patches' E = pi * Ke.")
      .def_readonly("file", &Material::file, "The MTL file that defines it (str; empty if none).")
      .def_readonly("line", &Material::line, "Its line in that file (int, from 1; 0 if none).")
      .def("__repr__", [](const Material& x) { return "<radwalk.Material '" + x.name + "'>"; });

  py::class_<Scene>(m, "Scene", R"doc(A validated, patched scene (radwalk.load).

Per-patch numpy arrays are views of the C++ arrays (no copy; they keep the Scene alive):
  areas (N,), centroids (N, 3), normals (N, 3), face (N,) input face, material (N,) index into materials,
  group (N,) index into groups (-1 outside any), points (P, 3) and corners (N, 4) (-1 in [3] for a triangle):
  read-only;
  rho (N, 3) and E (N, 3): WRITABLE in place. Every later computation (form_factors excepted: F does not depend on
  them) uses the values as they are then, e.g. scene.rho[scene.material == 2] = 0.5. Values outside what an MTL
  may hold are not refused when written but by every computation before it starts (InputError naming the patch,
  channel and value): rho in [0, 1), E = pi Ke finite, >= 0 and at most pi x 1e300.
Per material: set_material(name, rho=..., Ke=...), which acts as the same scene with an edited MTL.)doc")
      .def_readonly("path", &Scene::path, "The scene file read (str); \"<arrays>\" or \"<meshio>\" for a scene from arrays.")
      .def_readonly("max_edge", &Scene::max_edge,
                    "The max_edge it was patched with (float, mesh length units; 0: input faces kept).")
      .def_readonly("max_area", &Scene::max_area,
                    "The max_area it was patched with (float, mesh length units squared; 0: no bound).")
      .def_readonly("strict", &Scene::strict, "Whether repairs were refused (bool), as the CLI's --strict.")
      .def_readonly("two_sided", &Scene::two_sided, "Whether every material was made two-sided (bool), as --two-sided.")
      .def_readonly("orient", &Scene::orient, "The orientation it was read with (str), as --orient.")
      .def_readonly("open_shells", &Scene::open_shells, "The sides given to open shells (str), as --open-shells.")
      .def_readonly("scale", &Scene::scale, "The factor every coordinate was multiplied by (float), as --scale.")
      .def_readonly("unit", &Scene::unit, "The file's unit as given (str; \"\" for the file's own), as --unit.")
      .def_readonly("length_unit", &Scene::length_unit,
                    "The unit of lengths after scaling (str: \"m\", \"mesh unit\", ...), as the CLI's summaries name it.")
      .def_readonly("radiosity_unit", &Scene::radiosity_unit, "The unit of B (str: \"W/m^2\", ...).")
      .def_readonly("contact_cut", &Scene::contact_cut,
                    "Whether faces are cut along contacts when they are split (bool), as --contact-cut (the default).")
      .def_readonly("cut", &Scene::cut,
                    "Whether faces were cut along the footprints and lines of objects touching them (bool): "
                    "contact_cut and a split (max_edge or max_area).")
      .def_readonly("warnings", &Scene::warnings, "Validation's repairs and notices, a list of str, one line each (as the CLI's).")
      .def_readonly("notes", &Scene::notes,
                    "Validation's notes, a list of str, one line each (the CLI's \"note:\" lines: how the file was read, "
                    "e.g. that an --orient given re-orients a file radwalk wrote).")
      .def_readonly("groups", &Scene::group_names,
                    "Group names (a list of str), indexed by Scene.group: the groups that hold a patch, each as the file names it: "
                    "'desk' (an OBJ object or a group alone), 'desk/top' (group 'top' within object 'desk').")
      .def_property_readonly("materials", [](const Scene& s) { return s.patches.materials; },
                             "The materials (a list of Material, copies), indexed by Scene.material.")
      .def_static("from_arrays", &from_arrays, py::arg("vertices"), py::arg("faces"), py::arg("rho"),
                  py::arg("emission") = py::none(), py::arg("groups") = py::none(), py::arg("two_sided") = false,
                  py::arg("max_edge") = 0.0, py::arg("max_area") = 0.0, py::arg("strict") = false,
                  py::arg("contact_cut") = true,
                  R"doc(A Scene from numpy arrays, validated and patched as radwalk.load would the same mesh as a file.

vertices: (V, 3) float coordinates, in the mesh's length unit.
faces: (F, 3) or (F, 4) integer array of 0-based vertex indices (counter-clockwise seen from the front), or a
  list of F lists of 3 or more indices (polygons are triangulated as the readers do).
rho: reflectance per face, (F, 3) or (F,) (grey) or one number, each in [0, 1).
emission: emitted radiosity E per face in W/m^2 (exitance: Ke = E / pi), (F, 3), (F,) or one number; None: 0.
groups: None or one name (str) per face ("" for none), as OBJ `g NAME`.
two_sided, max_edge, max_area, strict, contact_cut: as radwalk.load.
The materials are the distinct (rho, E) pairs, named "material_0", ... in the order of their first face; the OBJ
and MTL that say the same give the same patches and the same repairs, warnings and refusals (InputError).)doc")
      .def("__len__", [](const Scene& s) { return s.patches.size(); }, "The number of patches N (int).")
      .def_property_readonly("total_area", [](const Scene& s) { return s.patches.total_area(); },
                             "The sum of the patch areas (float, mesh length units squared).")
      .def_property_readonly(
          "areas", [](py::object self) {
            const Scene& s = self.cast<const Scene&>();
            return view(s.patches.area.data(), s.patches.size(), 1, self, false, sizeof(double));
          }, "Patch areas (N,) float64, in mesh length units squared.")
      .def_property_readonly(
          "centroids", [](py::object self) {
            const Scene& s = self.cast<const Scene&>();
            return view(s.patches.centroid.data()->data(), s.patches.size(), 3, self, false, sizeof(Vec3));
          }, "Area centroids (N, 3) float64, in mesh length units.")
      .def_property_readonly(
          "normals", [](py::object self) {
            const Scene& s = self.cast<const Scene&>();
            return view(s.patches.normal.data()->data(), s.patches.size(), 3, self, false, sizeof(Vec3));
          }, "Unit normals (N, 3) float64, from the corner order (counter-clockwise seen from the front).")
      .def_property_readonly(
          "points", [](py::object self) {
            const Scene& s = self.cast<const Scene&>();
            return view(s.patches.points.data()->data(), s.patches.points.size(), 3, self, false, sizeof(Vec3));
          }, "Corner points (P, 3) float64 in mesh length units, shared between patches.")
      .def_property_readonly(
          "corners", [](py::object self) {
            const Scene& s = self.cast<const Scene&>();
            return view(s.patches.corners.data()->data(), s.patches.size(), 4, self, false, 4 * sizeof(std::int32_t));
          }, "Corner indices into points (N, 4) int32; corners[i, 3] == -1 for a triangle.")
      .def_property_readonly(
          "face", [](py::object self) {
            const Scene& s = self.cast<const Scene&>();
            return view(s.patches.face.data(), s.patches.size(), 1, self, false, sizeof(std::int32_t));
          }, "Input face of every patch (N,) int32, counted from 0 in file order.")
      .def_property_readonly(
          "material", [](py::object self) {
            const Scene& s = self.cast<const Scene&>();
            return view(s.patches.material.data(), s.patches.size(), 1, self, false, sizeof(std::int32_t));
          }, "Material index of every patch (N,) int32, into Scene.materials.")
      .def_property_readonly(
          "group", [](py::object self) {
            const Scene& s = self.cast<const Scene&>();
            return view(s.group.data(), s.patches.size(), 1, self, false, sizeof(std::int32_t));
          }, "Group index of every patch (N,) int32, into Scene.groups; -1 outside any group.")
      .def_property(
          "rho", [](py::object self) {
            Scene& s = self.cast<Scene&>();
            return view(s.patches.rho.data()->data(), s.patches.size(), 3, self, true, sizeof(Rgb));
          },
          [](py::object self, py::object values) { assign(self.attr("rho"), values); },
          "Diffuse reflectance (N, 3) float64, dimensionless in [0, 1), writable in place: scene.rho[i] = (r, g, b), "
          "scene.rho[:] *= 0.9.")
      .def_property(
          "E", [](py::object self) {
            Scene& s = self.cast<Scene&>();
            return view(s.patches.E.data()->data(), s.patches.size(), 3, self, true, sizeof(Rgb));
          },
          [](py::object self, py::object values) { assign(self.attr("E"), values); },
          "Emitted radiosity E = pi * Ke (N, 3) float64, W per unit length squared, writable in place.")
      .def(
          "set_material", &set_material,
          py::arg("material"), py::arg("rho") = py::none(), py::arg("Ke") = py::none(),
          R"doc(Sets a material's Kd (rho) and/or Ke (emitted radiance), by name or index, as an edited MTL would.

rho and Ke: a number (all three channels) or (r, g, b); refused (InputError) outside what an MTL may hold:
rho in [0, 1), Ke finite, >= 0 and at most 1e300.
Then every patch's rho and E are derived again from its material (rho = Kd, E = pi * Ke: the library's
set_radiometry_from_materials), so per-patch edits of rho or E made before are replaced.)doc")
      .def("__repr__", [](const Scene& s) {
        return "<radwalk.Scene '" + s.path + "': " + std::to_string(s.patches.size()) + " patches, " +
               std::to_string(s.patches.materials.size()) + " materials>";
      });

  m.def("load", &load, py::arg("path"), py::arg("max_edge") = 0.0, py::arg("max_area") = 0.0,
        py::arg("strict") = false, py::arg("two_sided") = false, py::arg("contact_cut") = true,
        py::arg("orient") = py::none(), py::arg("open_shells") = "auto", py::arg("scale") = 1.0,
        py::arg("unit") = py::none(), py::arg("set") = py::none(), py::arg("rho_scale") = 1.0,
        R"doc(Reads, validates and patches a scene (OBJ with MTL, PLY, STL, glTF/GLB, .vtp/.vtk): a Scene.

max_edge: split faces until no patch edge is longer than this (mesh units); 0 keeps the input faces (patch i is
  input face i), as the CLI's --max-edge.
max_area: also split faces until no patch is larger than this (mesh units squared), as --max-area.
strict: refuse what validation would repair (the CLI's --strict).
two_sided: every material two-sided (a front and a back patch per face), as --two-sided; materials with
  `radwalk_two_sided 1` in their MTL block are two-sided either way.
contact_cut: cut the faces that objects stand on along their footprints and contact lines before splitting (True,
  the default, as the CLI's --contact-cut; False as --no-contact-cut). The cut is made when max_edge or max_area
  splits faces; with neither, the input faces stay the patches, and solve_to_target_error cuts them before its own
  split.
orient: "outward" (faces agree with their shells' neighbours, closed objects face out, the enclosing room in),
  "consistent" or "none", as --orient; None (the default) is "outward", except that a .vtp or .obj radwalk wrote
  keeps the orientation its run gave its patches, as when --orient is left out.
open_shells: "auto" (two-sided inside a closed room, one-sided in an open scene), "one-sided" or "two-sided", as
  --open-shells.
scale: every coordinate times this before anything else (lengths, areas, max_edge and B in the scaled unit), as
  --scale; unit: the file's unit ("mm", "cm", "m", "in", "ft" or None), as --unit; the unit after scaling is
  Scene.length_unit, that of B Scene.radiosity_unit.
set: material overrides, one str or a list of them, "NAME.Kd=r,g,b" or "NAME.Ke=r,g,b" (one number: grey), as
  --set (the only way to give STL solids and VTK surfaces without rho their reflectance); rho_scale: every Kd
  times this after the overrides, as --rho-scale.
Repairs are reported as one UserWarning that counts them and kept in Scene.warnings; refusals raise radwalk.InputError (a
ValueError) with the CLI's one-line message ("FILE:LINE: face F: what is wrong").)doc");
}

}  // namespace radwalk::python
