// The streaming .vtp writer (io/vtp_writer.cpp, io/vtk_binary.h): what VTK's own reader reads back equals what was
// written, value for value, for arrays of several zlib blocks; and the base64 and block layout it relies on.
#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkPointData.h>
#include <vtkStringArray.h>
#include <vtkTypeInt64Array.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/srgb.h"
#include "io/vtk_binary.h"
#include "io/vtp_writer.h"
#include "patch/display_mesh.h"
#include "patch/patch_builder.h"
#include "vtp_test_helpers.h"

using namespace radwalk;

namespace {

std::string base64_of(const std::string& bytes, std::size_t piece) {
  std::ostringstream out;
  Base64Writer w(out);
  for (std::size_t k = 0; k < bytes.size(); k += piece) w.put(bytes.data() + k, std::min(piece, bytes.size() - k));
  w.finish();
  return out.str();
}

// Decodes base64 text (no whitespace) up to its first padding or its end; `used` gets the characters consumed.
std::string base64_decode(const std::string& text, std::size_t& used) {
  const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string bytes;
  used = 0;
  for (; used + 4 <= text.size(); used += 4) {
    std::uint32_t v = 0;
    int pad = 0;
    for (int c = 0; c < 4; ++c) {
      const char ch = text[used + c];
      pad += ch == '=';
      v = (v << 6) | (ch == '=' ? 0u : std::uint32_t(alphabet.find(ch)));
    }
    bytes.push_back(char(v >> 16));
    if (pad < 2) bytes.push_back(char(v >> 8));
    if (pad < 1) bytes.push_back(char(v));
    if (pad > 0) {
      used += 4;
      break;
    }
  }
  return bytes;
}

// A grid of nx x ny welded unit quads on z = 0 (points shared, so the point fields average four patches), the
// first row an emitter (its own smoothing group).
PatchSet grid(int nx, int ny) {
  PatchBuilder b;
  const int wall = b.add_material("wall", Rgb(0.73, 0.5, 0.25));
  const int light = b.add_material("light", Rgb(0.1, 0.2, 0.3), Rgb(1, 2, 3));
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      b.add_quad({double(i), double(j), 0}, {i + 1.0, double(j), 0}, {i + 1.0, j + 1.0, 0}, {double(i), j + 1.0, 0},
                 j == 0 ? light : wall);
  PatchSet p = b.build();
  weld_points(p);
  return p;
}

// Reads `path` with VTK's reader, counting the errors and warnings it reports.
struct ReadBack {
  vtkSmartPointer<vtkPolyData> poly;
  int errors = 0;
};
ReadBack read_counting_errors(const std::string& path) {
  ReadBack r;
  vtkNew<vtkCallbackCommand> count;
  count->SetClientData(&r.errors);
  count->SetCallback([](vtkObject*, unsigned long, void* errors, void*) { ++*static_cast<int*>(errors); });
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->AddObserver(vtkCommand::ErrorEvent, count);
  reader->AddObserver(vtkCommand::WarningEvent, count);
  reader->SetFileName(path.c_str());
  reader->Update();
  r.poly = reader->GetOutput();
  return r;
}

std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Every value of VTK array a equals values (tuples x components, tuple-major), exactly (NaN matches NaN).
template <class T>
void check_values(vtkDataArray* a, const std::vector<T>& values, int components) {
  REQUIRE(a != nullptr);
  INFO(a->GetName());
  REQUIRE(a->GetNumberOfComponents() == components);
  REQUIRE(static_cast<std::size_t>(a->GetNumberOfTuples()) * components == values.size());
  std::size_t wrong = 0;
  for (std::size_t k = 0; k < values.size(); ++k) {
    const double got = a->GetComponent(vtkIdType(k / components), int(k % components));
    const double want = static_cast<double>(values[k]);
    wrong += !(got == want || (std::isnan(got) && std::isnan(want)));
  }
  CHECK(wrong == 0);
}

}  // namespace

TEST_CASE("Base64Writer: RFC 4648 test vectors, whatever the pieces the bytes come in", "[io][vtp]") {
  // RFC 4648, section 10.
  const std::pair<const char*, const char*> vectors[] = {{"", ""},         {"f", "Zg=="},         {"fo", "Zm8="},
                                                         {"foo", "Zm9v"},  {"foob", "Zm9vYg=="}, {"fooba", "Zm9vYmE="},
                                                         {"foobar", "Zm9vYmFy"}};
  for (const auto& [bytes, text] : vectors)
    for (std::size_t piece : {1, 2, 3, 4, 7}) {
      INFO(bytes << " in pieces of " << piece);
      CHECK(base64_of(bytes, piece) == text);
    }
  // Every byte value, across the 4096-character buffer.
  std::string all;
  for (int k = 0; k < 10000; ++k) all.push_back(char(k * 37 % 256));
  const std::string text = base64_of(all, 1000);
  std::size_t used = 0;
  CHECK(base64_decode(text, used) == all);
  CHECK(used == text.size());
}

TEST_CASE("write_vtp: VTK reads back what was written, arrays of several zlib blocks", "[io][vtp]") {
  // 60 x 60 patches: each 3-component double array is 86,400 bytes (3 blocks of 32 KiB), B_srgb 10,800 bytes.
  const PatchSet patches = grid(60, 60);
  const std::size_t n = patches.size();
  std::vector<CellField> fields = patch_fields(patches);
  PatchRgb B(static_cast<Eigen::Index>(n), 3);
  std::vector<double> rays(n), noise(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) B(Eigen::Index(i), c) = 0.5 + 0.45 * std::sin(0.37 * double(i) + c) * (c + 1);
    rays[i] = double((std::int64_t{1} << 40) + std::int64_t(i) * 977);  // beyond 32 bits
    noise[i] = std::sin(1e4 * double(i));                                 // incompressible
  }
  B(7, 1) = std::numeric_limits<double>::quiet_NaN();  // a patch with no estimate: NaN stays NaN
  fields.push_back(rgb_field("B", B));
  fields.push_back(scalar_field("rays", rays, FieldKind::count));
  fields.push_back(scalar_field("noise", noise));
  VtpMetadata m;
  m.set_text("command_line", "radwalk solve scene.obj --particles 10000000");
  m.set_text("empty", "");
  m.set_real("residual", 1.5e-11);
  m.set_integer("seed", -(std::int64_t{1} << 50));

  const auto path = temp_file("radwalk_streaming.vtp");
  write_vtp(path, patches, fields, m);
  const ReadBack r = read_counting_errors(path);
  CHECK(r.errors == 0);
  vtkPolyData* poly = r.poly;
  const DisplayMesh mesh = make_display_mesh(patches);
  REQUIRE(static_cast<std::size_t>(poly->GetNumberOfCells()) == n);
  REQUIRE(static_cast<std::size_t>(poly->GetNumberOfPoints()) == mesh.points.size());

  // Geometry: the display mesh's points and polygons.
  std::vector<double> xyz;
  for (const Vec3& q : mesh.points) xyz.insert(xyz.end(), {q.x(), q.y(), q.z()});
  check_values(poly->GetPoints()->GetData(), xyz, 3);
  std::size_t wrong_polygons = 0;
  vtkNew<vtkIdList> ids;
  for (std::size_t i = 0; i < n; ++i) {
    poly->GetCellPoints(vtkIdType(i), ids);
    bool same = ids->GetNumberOfIds() == mesh.offsets[i + 1] - mesh.offsets[i];
    for (vtkIdType k = 0; same && k < ids->GetNumberOfIds(); ++k) same = ids->GetId(k) == mesh.ids[mesh.offsets[i] + k];
    wrong_polygons += !same;
  }
  CHECK(wrong_polygons == 0);
  CHECK(poly->GetVerts()->GetNumberOfCells() == 0);
  CHECK(poly->GetLines()->GetNumberOfCells() == 0);

  // Cell data: every field with its type and names (the radiosity's triple as B_rgb), B_srgb, the active scalars B
  // (the channel mean).
  const auto array_name = [](const CellField& f) { return f.name == "B" ? std::string("B_rgb") : f.name; };
  vtkCellData* cells = poly->GetCellData();
  for (const CellField& f : fields) {
    INFO(f.name);
    vtkDataArray* a = cells->GetArray(array_name(f).c_str());
    REQUIRE(a != nullptr);
    CHECK(a->GetDataType() == (f.kind == FieldKind::count ? VTK_LONG_LONG : VTK_DOUBLE));
    if (f.kind == FieldKind::count) {
      std::vector<std::int64_t> counts(f.values.begin(), f.values.end());
      check_values(a, counts, f.components);
    } else {
      check_values(a, f.values, f.components);
    }
    const bool rgb = f.kind == FieldKind::quantity && f.components == 3;
    CHECK((a->GetComponentName(0) != nullptr) == rgb);
    if (rgb) CHECK(std::string(a->GetComponentName(2)) == "B");
  }
  CHECK(cells->GetNumberOfArrays() == int(fields.size()) + 3);  // B_rgb, B_srgb, material_id
  REQUIRE(cells->GetScalars() != nullptr);
  CHECK(std::string(cells->GetScalars()->GetName()) == "B");
  const std::vector<double>& b = fields[fields.size() - 3].values;
  std::vector<double> b_mean(b.size() / 3);
  for (std::size_t k = 0; k < b_mean.size(); ++k) b_mean[k] = (b[3 * k] + b[3 * k + 1] + b[3 * k + 2]) / 3.0;
  check_values(cells->GetScalars(), b_mean, 1);
  std::vector<unsigned char> srgb(b.size());
  for (std::size_t k = 0; k < b.size(); ++k) srgb[k] = srgb8_from_radiosity(b[k]);
  REQUIRE(cells->GetArray("B_srgb") != nullptr);
  CHECK(cells->GetArray("B_srgb")->GetDataType() == VTK_UNSIGNED_CHAR);
  check_values(cells->GetArray("B_srgb"), srgb, 3);

  // Point data: the point average of each quantity field (patch/display_mesh.h), and B_srgb of B's.
  vtkPointData* points = poly->GetPointData();
  int quantities = 0;
  for (const CellField& f : fields) {
    if (f.kind != FieldKind::quantity) {
      CHECK(points->GetArray(f.name.c_str()) == nullptr);
      continue;
    }
    ++quantities;
    check_values(points->GetArray(array_name(f).c_str()), point_average(mesh, patches, f.values, f.components),
                 f.components);
  }
  const std::vector<double> b_points = point_average(mesh, patches, b, 3);
  std::vector<unsigned char> srgb_points(b_points.size());
  for (std::size_t k = 0; k < b_points.size(); ++k) srgb_points[k] = srgb8_from_radiosity(b_points[k]);
  check_values(points->GetArray("B_srgb"), srgb_points, 3);
  REQUIRE(points->GetArray("B") != nullptr);
  CHECK(points->GetArray("B")->GetNumberOfComponents() == 1);
  CHECK(points->GetNumberOfArrays() == quantities + 2);
  CHECK(points->GetScalars() == nullptr);

  // Field data: text (the empty one too), real and a 64-bit integer, in the order set.
  vtkFieldData* fd = poly->GetFieldData();
  REQUIRE(fd->GetNumberOfArrays() == 5);  // and material_names
  CHECK(std::string(fd->GetAbstractArray(0)->GetName()) == "command_line");
  auto* text = vtkStringArray::SafeDownCast(fd->GetAbstractArray("command_line"));
  REQUIRE(text != nullptr);
  CHECK(text->GetValue(0) == "radwalk solve scene.obj --particles 10000000");
  auto* empty = vtkStringArray::SafeDownCast(fd->GetAbstractArray("empty"));
  REQUIRE(empty != nullptr);
  CHECK(empty->GetNumberOfValues() == 1);
  CHECK(empty->GetValue(0).empty());
  REQUIRE(fd->GetArray("residual") != nullptr);
  CHECK(fd->GetArray("residual")->GetDataType() == VTK_DOUBLE);
  CHECK(fd->GetArray("residual")->GetComponent(0, 0) == 1.5e-11);
  REQUIRE(fd->GetArray("seed") != nullptr);
  CHECK(fd->GetArray("seed")->GetDataType() == VTK_LONG_LONG);
  CHECK(vtkArrayDownCast<vtkTypeInt64Array>(fd->GetArray("seed"))->GetValue(0) == -(std::int64_t{1} << 50));

  // The layout is the one asked for: UInt64 headers, and B_rgb is cut into several blocks.
  const std::string s = file_text(path);
  CHECK(s.find("header_type=\"UInt64\"") != std::string::npos);
  CHECK(s.find("compressor=\"vtkZLibDataCompressor\"") != std::string::npos);
  const std::size_t at = s.find("<DataArray type=\"Float64\" Name=\"B_rgb\"", s.find("<CellData"));
  REQUIRE(at != std::string::npos);
  const std::size_t begin = s.find_first_not_of(" \n", s.find('>', at) + 1);
  std::size_t used = 0;
  const std::string header = base64_decode(s.substr(begin, 64), used);
  REQUIRE(header.size() >= 24);
  std::uint64_t h[3];
  std::memcpy(h, header.data(), sizeof h);
  CHECK(h[0] == (n * 3 * 8 + kVtkBlockBytes - 1) / kVtkBlockBytes);
  CHECK(h[0] >= 3);
  CHECK(h[1] == kVtkBlockBytes);
  CHECK(h[2] == n * 3 * 8 % kVtkBlockBytes);
  std::filesystem::remove(path);
}

TEST_CASE("write_vtp: no patches and no fields is an empty data set VTK reads", "[io][vtp]") {
  const auto path = temp_file("radwalk_streaming_empty.vtp");
  write_vtp(path, PatchSet{}, {});
  const ReadBack r = read_counting_errors(path);
  CHECK(r.errors == 0);
  CHECK(r.poly->GetNumberOfCells() == 0);
  CHECK(r.poly->GetNumberOfPoints() == 0);
  std::filesystem::remove(path);
}
