#include "io/vtp_writer.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <ostream>
#include <stdexcept>

#include "core/atomic_write.h"
#include "core/check.h"
#include "core/error.h"
#include "core/srgb.h"
#include "io/vtk_binary.h"
#include "patch/display_mesh.h"

namespace radwalk {
namespace {

// The file is VTK XML PolyData written here, one array at a time, straight into the atomic writer's stream: each
// DataArray inline (format="binary", io/vtk_binary.h), so that no offsets into the file are needed before the
// data exist, and each point field is computed, encoded, written and freed before the next. The layout is VTK's
// own (what vtkXMLPolyDataWriter writes in binary mode with zlib): field data, then the piece's point data, cell
// data, points and cells (vertices, lines and strips empty; polygon offsets are the end of each polygon in the
// connectivity, without the leading 0).

void check_name(const std::string& name) {
  if (name.empty() || paraview_name(name) != name || is_calculator_reserved(name) ||
      std::isdigit(static_cast<unsigned char>(name[0])))
    throw std::logic_error("write_vtp: '" + name + "' is not a name ParaView's Calculator accepts");
}

// The shortest text that reads back as x (std::to_chars).
std::string number_text(double x) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, x).ptr;
  return std::string(text, end);
}

template <class T>
constexpr const char* vtk_type_name() {
  if constexpr (std::is_same_v<T, double>) return "Float64";
  if constexpr (std::is_same_v<T, std::int64_t>) return "Int64";
  if constexpr (std::is_same_v<T, unsigned char>) return "UInt8";
}

// What an array element says about the values besides its name and type.
struct ArrayLayout {
  int components = 1;
  bool rgb = false;            // component names R, G, B
  std::size_t tuples_attr = 0;  // > 0: NumberOfTuples attribute (field data)
  const char* units = nullptr;  // the array's vtkDataArray::UNITS_LABEL, or none
};

// The unit of the radiosity arrays B and B_rgb: W per square length unit of the scene (W/m^2 for metres).
constexpr const char* kRadiosityUnits = "W/unit^2";

// ' RangeMin="..." RangeMax="..."' as VTK writes them: the range of the values (one component) or of the tuples'
// Euclidean norms, over the finite ones; "" when none is finite.
template <class T>
std::string range_attributes(const T* values, std::size_t tuples, int components) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t t = 0; t < tuples; ++t) {
    double r = 0;
    if (components == 1) {
      r = static_cast<double>(values[t]);
    } else {
      for (int c = 0; c < components; ++c) {
        const double v = static_cast<double>(values[t * static_cast<std::size_t>(components) + c]);
        r += v * v;
      }
      r = std::sqrt(r);
    }
    if (!std::isfinite(r)) continue;
    lo = std::min(lo, r);
    hi = std::max(hi, r);
  }
  if (!(lo <= hi)) return "";
  return " RangeMin=\"" + number_text(lo) + "\" RangeMax=\"" + number_text(hi) + "\"";
}

// One <DataArray> of `tuples` x layout.components values at `values`, at indentation `indent`.
template <class T>
void write_data_array(std::ostream& out, const std::string& indent, const std::string& name, const T* values,
                      std::size_t tuples, const ArrayLayout& layout) {
  out << indent << "<DataArray type=\"" << vtk_type_name<T>() << "\" Name=\"" << name << "\"";
  if (layout.components != 1) out << " NumberOfComponents=\"" << layout.components << "\"";
  if (layout.rgb) out << " ComponentName0=\"R\" ComponentName1=\"G\" ComponentName2=\"B\"";
  if (layout.tuples_attr > 0) out << " NumberOfTuples=\"" << layout.tuples_attr << "\"";
  out << " format=\"binary\"" << range_attributes(values, tuples, layout.components) << ">\n" << indent << "  ";
  write_vtk_compressed_base64(out, values, tuples * static_cast<std::size_t>(layout.components) * sizeof(T));
  out << "\n";
  if (layout.units)  // after the data, as vtkXMLWriter writes an array's information keys
    out << indent << "  <InformationKey name=\"UNITS_LABEL\" location=\"vtkDataArray\">" << layout.units
        << "</InformationKey>\n";
  out << indent << "</DataArray>\n";
}

// The names of the patches (vtp_writer.h): the tables of distinct object, group and material names and each
// patch's index into them (-1: none).
struct NameTables {
  std::vector<std::string> objects, groups, materials;
  std::vector<std::int64_t> object_id, group_id, material_id;
};

NameTables name_tables(const PatchSet& patches) {
  NameTables t;
  for (const Material& m : patches.materials) t.materials.push_back(m.name);
  auto index_in = [](std::vector<std::string>& table, const std::string& name) -> std::int64_t {
    if (name.empty()) return -1;
    for (std::size_t k = 0; k < table.size(); ++k)
      if (table[k] == name) return static_cast<std::int64_t>(k);
    table.push_back(name);
    return static_cast<std::int64_t>(table.size() - 1);
  };
  for (std::size_t i = 0; i < patches.size(); ++i) {
    t.object_id.push_back(index_in(t.objects, patches.object_of(i)));
    t.group_id.push_back(index_in(t.groups, patches.group_of(i)));
    t.material_id.push_back(patches.material[i]);
  }
  return t;
}

// A string array of field data: each string followed by a NUL, which is how VTK stores strings in binary arrays.
void write_string_array(std::ostream& out, const std::string& name, const std::vector<std::string>& values) {
  std::string bytes;
  for (const std::string& v : values) {
    bytes += v;
    bytes.push_back('\0');
  }
  out << "      <Array type=\"String\" Name=\"" << name << "\" NumberOfTuples=\"" << values.size()
      << "\" format=\"binary\">\n        ";
  write_vtk_compressed_base64(out, bytes.data(), bytes.size());
  out << "\n      </Array>\n";
}

// The run's metadata as one-tuple arrays (vtp_metadata.h), then the name tables (object_names, group_names,
// material_names; each written when it has a name).
void write_field_data(std::ostream& out, const VtpMetadata& metadata, const NameTables& names) {
  if (metadata.entries.empty() && names.objects.empty() && names.groups.empty() && names.materials.empty()) return;
  out << "    <FieldData>\n";
  ArrayLayout one;
  one.tuples_attr = 1;
  for (const auto& [key, value] : metadata.entries) {
    if (const auto* text = std::get_if<std::string>(&value)) {
      write_string_array(out, key, {*text});
    } else if (const auto* real = std::get_if<double>(&value)) {
      write_data_array(out, "      ", key, real, 1, one);
    } else {
      write_data_array(out, "      ", key, &std::get<std::int64_t>(value), 1, one);
    }
  }
  if (!names.objects.empty()) write_string_array(out, "object_names", names.objects);
  if (!names.groups.empty()) write_string_array(out, "group_names", names.groups);
  if (!names.materials.empty()) write_string_array(out, "material_names", names.materials);
  out << "    </FieldData>\n";
}

// B_srgb (core/srgb.h) of the RGB values: 8-bit sRGB per channel.
std::vector<unsigned char> srgb_of(const std::vector<double>& rgb) {
  std::vector<unsigned char> s(rgb.size());
  for (std::size_t k = 0; k < rgb.size(); ++k) s[k] = srgb8_from_radiosity(rgb[k]);
  return s;
}

ArrayLayout rgb_layout() {
  ArrayLayout l;
  l.components = 3;
  l.rgb = true;
  return l;
}

bool is_radiosity(const CellField& f) { return f.name == "B" && f.components == 3 && f.kind == FieldKind::quantity; }

// The channel mean (R + G + B) / 3 of each tuple of an RGB array: the one-component B.
std::vector<double> channel_mean(const std::vector<double>& rgb) {
  std::vector<double> mean(rgb.size() / 3);
  for (std::size_t k = 0; k < mean.size(); ++k) mean[k] = (rgb[3 * k] + rgb[3 * k + 1] + rgb[3 * k + 2]) / 3.0;
  return mean;
}

// The radiosity B given as RGB, as three arrays: B (the channel mean, the active scalars), B_rgb (the triple), both
// with the unit kRadiosityUnits as their UNITS_LABEL, and B_srgb (its display colour).
void write_radiosity(std::ostream& out, const std::string& indent, const std::vector<double>& rgb, std::size_t n) {
  ArrayLayout mean;
  mean.units = kRadiosityUnits;
  ArrayLayout triple = rgb_layout();
  triple.units = kRadiosityUnits;
  write_data_array(out, indent, "B", channel_mean(rgb).data(), n, mean);
  write_data_array(out, indent, "B_rgb", rgb.data(), n, triple);
  write_data_array(out, indent, "B_srgb", srgb_of(rgb).data(), n, rgb_layout());
}

ArrayLayout layout_of(const CellField& f) {
  ArrayLayout l;
  l.components = f.components;
  l.rgb = f.kind == FieldKind::quantity && f.components == 3;
  return l;
}

// The point data: each quantity field averaged at the display points (B as B, B_rgb, B_srgb of the average); each
// computed, written and freed before the next.
void write_point_data(std::ostream& out, const DisplayMesh& mesh, const PatchSet& patches,
                      const std::vector<const CellField*>& fields, const std::string& path) {
  out << "      <PointData>\n";
  const std::size_t m = mesh.points.size();
  for (const CellField* f : fields) {
    if (f->kind != FieldKind::quantity) continue;
    const std::vector<double> at_points = point_average(mesh, patches, f->values, f->components);
    if (is_radiosity(*f))
      write_radiosity(out, "        ", at_points, m);
    else
      write_data_array(out, "        ", f->name, at_points.data(), m, layout_of(*f));
    if (!out) throw InputError(path + ": write failed (disk full?)");
  }
  out << "      </PointData>\n";
}

// The cell data: every field, counts as Int64, the others as Float64, the radiosity as B, B_rgb, B_srgb.
void write_cell_data(std::ostream& out, std::size_t n, const std::vector<const CellField*>& fields,
                     const NameTables& names, const std::string& path) {
  bool radiosity = false;
  for (const CellField* f : fields) radiosity = radiosity || is_radiosity(*f);
  out << "      <CellData" << (radiosity ? " Scalars=\"B\"" : "") << ">\n";
  for (const CellField* f : fields) {
    if (f->kind == FieldKind::count) {
      std::vector<std::int64_t> counts(f->values.size());
      for (std::size_t k = 0; k < counts.size(); ++k) counts[k] = static_cast<std::int64_t>(std::llround(f->values[k]));
      write_data_array(out, "        ", f->name, counts.data(), n, layout_of(*f));
      continue;
    }
    if (is_radiosity(*f))
      write_radiosity(out, "        ", f->values, n);
    else
      write_data_array(out, "        ", f->name, f->values.data(), n, layout_of(*f));
    if (!out) throw InputError(path + ": write failed (disk full?)");
  }
  // The patches' names as indices into the field data's tables (Int64, -1 for none).
  if (!names.objects.empty()) write_data_array(out, "        ", "object_id", names.object_id.data(), n, {});
  if (!names.groups.empty()) write_data_array(out, "        ", "group_id", names.group_id.data(), n, {});
  if (!names.materials.empty()) write_data_array(out, "        ", "material_id", names.material_id.data(), n, {});
  out << "      </CellData>\n";
}

// Empty cells of one kind (vertices, lines, strips), as VTK writes them.
void write_no_cells(std::ostream& out, const char* element) {
  const std::int64_t none = 0;
  out << "      <" << element << ">\n";
  write_data_array(out, "        ", "connectivity", &none, 0, {});
  write_data_array(out, "        ", "offsets", &none, 0, {});
  out << "      </" << element << ">\n";
}

}  // namespace

void write_vtp_fields(const std::string& path, const PatchSet& patches, const std::vector<const CellField*>& fields,
                      const VtpMetadata& metadata, const DisplayMesh* given_mesh) {
  const std::size_t n = patches.size();
  // Everything that can be refused is checked before the file is created.
  bool radiosity = false;
  for (const CellField* f : fields) radiosity = radiosity || is_radiosity(*f);
  for (const CellField* f : fields) {
    check_name(f->name);
    if (radiosity && (f->name == "B_rgb" || f->name == "B_srgb"))
      throw std::logic_error("write_vtp: '" + f->name + "' is written from the radiosity B; give B (RGB) only");
    RADWALK_CHECK_EQ(f->values.size(), n * static_cast<std::size_t>(f->components));  // a value per patch, component
  }
  for (const auto& entry : metadata.entries) check_name(entry.first);
  for (const CellField* f : fields)
    if (f->name == "object_id" || f->name == "group_id" || f->name == "material_id")
      throw std::logic_error("write_vtp: '" + f->name + "' is written from the patches' names");
  DisplayMesh built;
  if (!given_mesh) built = make_display_mesh(patches);
  const DisplayMesh& mesh = given_mesh ? *given_mesh : built;
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "display points are packed xyz triples");
  RADWALK_CHECK_EQ(mesh.offsets.size(), n + 1);

  write_atomically(path, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n"
           "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\" "
           "compressor=\"vtkZLibDataCompressor\">\n"
           "  <PolyData>\n";
    const NameTables names = name_tables(patches);
    write_field_data(out, metadata, names);
    out << "    <Piece NumberOfPoints=\"" << mesh.points.size()
        << "\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"" << n << "\">\n";
    write_point_data(out, mesh, patches, fields, path);
    write_cell_data(out, n, fields, names, path);
    out << "      <Points>\n";
    ArrayLayout xyz;
    xyz.components = 3;
    write_data_array(out, "        ", "Points", reinterpret_cast<const double*>(mesh.points.data()),
                     mesh.points.size(), xyz);
    out << "      </Points>\n";
    for (const char* element : {"Verts", "Lines", "Strips"}) write_no_cells(out, element);
    out << "      <Polys>\n";
    write_data_array(out, "        ", "connectivity", mesh.ids.data(), mesh.ids.size(), {});
    write_data_array(out, "        ", "offsets", mesh.offsets.data() + 1, n, {});
    out << "      </Polys>\n"
           "    </Piece>\n"
           "  </PolyData>\n"
           "</VTKFile>\n";
  });
}

void write_vtp(const std::string& path, const PatchSet& patches, const std::vector<CellField>& fields,
               const VtpMetadata& metadata) {
  std::vector<const CellField*> views;
  views.reserve(fields.size());
  for (const CellField& f : fields) views.push_back(&f);
  write_vtp_fields(path, patches, views, metadata);
}

void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& steps) {
  write_atomically(path, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
    for (const auto& [t, file] : steps)
      out << "    <DataSet timestep=\"" << t << "\" part=\"0\" file=\"" << file << "\"/>\n";
    out << "  </Collection>\n</VTKFile>\n";
  });
}

}  // namespace radwalk
