// radwalk's own .vtp reader (mesh/vtp_xml.h, mesh/vtk_data_array.h, mesh/read_vtk.h): every malformed class the
// vtk fuzz harness found in VTK 9.1's XML reader, and the layouts VTK's own writer (vtkXMLPolyDataWriter) writes,
// each read the same as the ascii file.
#include <catch2/catch.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkXMLPolyDataWriter.h>
#include <zlib.h>

#include "core/error.h"
#include "mesh/read_vtk.h"

using namespace radwalk;

namespace {

std::string base64(const std::string& bytes) {
  static const char* const kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t v = static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << 16;
    if (i + 1 < bytes.size()) v |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 2]);
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[v & 63] : '=';
  }
  return out;
}

// A little-endian UInt64 header word.
std::string word(std::uint64_t v) {
  std::string out;
  for (int k = 0; k < 8; ++k) out.push_back(static_cast<char>((v >> (8 * k)) & 0xff));
  return out;
}

std::string doubles(const std::vector<double>& v) {
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(double));
}

std::string zlib(const std::string& bytes) {
  uLongf size = compressBound(static_cast<uLong>(bytes.size()));
  std::string out(size, '\0');
  REQUIRE(compress2(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(bytes.data()),
                    static_cast<uLong>(bytes.size()), 5) == Z_OK);
  out.resize(size);
  return out;
}

// One zlib block holding `bytes`, declared as `declared` bytes: the header and the block, each in its own base64.
std::string compressed_base64(const std::string& bytes, std::uint64_t declared) {
  const std::string block = zlib(bytes);
  return base64(word(1) + word(declared) + word(declared) + word(block.size())) + base64(block);
}

const std::vector<double> kSquare = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};

// A square whose Points DataArray is `points` (the whole element), polygons `polys` (the elements inside <Polys>),
// field data `field` and the VTKFile attributes `file`; an <AppendedData> holding `appended` when it is not empty.
std::string vtp(const std::string& file, const std::string& points, const std::string& polys = "",
                const std::string& field = "", const std::string& appended = "") {
  const std::string p = polys.empty() ? "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0 1 2 3"
                                        "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">4"
                                        "</DataArray>\n"
                                      : polys;
  return "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\"" + file +
         ">\n<PolyData>\n" + field + "<Piece NumberOfPoints=\"4\" NumberOfPolys=\"1\">\n<Points>\n" + points +
         "\n</Points>\n<Polys>\n" + p + "</Polys>\n</Piece>\n</PolyData>\n" +
         (appended.empty() ? "" : "<AppendedData encoding=\"raw\">\n_" + appended + "\n</AppendedData>\n") +
         "</VTKFile>\n";
}

const std::string kPointsTag = "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=";
const std::string kZlib = " compressor=\"vtkZLibDataCompressor\"";

// `body` throws InputError whose message is one line, starts with `start` and contains `words`.
template <class Body>
void require_refusal(Body&& body, const std::string& start, const std::string& words) {
  try {
    body();
    FAIL("accepted; expected a refusal with '" << words << "'");
  } catch (const InputError& e) {
    const std::string m = e.what();
    INFO(m);
    REQUIRE(m.find('\n') == std::string::npos);
    REQUIRE(m.rfind(start, 0) == 0);
    REQUIRE(m.find(words) != std::string::npos);
  }
}

Mesh read(const std::string& text) { return read_vtk_polydata_bytes("f.vtp", text, true); }

}  // namespace

TEST_CASE("vtk .vtp reader: the square in every encoding radwalk reads", "[mesh][vtp]") {
  const std::string data = doubles(kSquare);
  const std::vector<std::string> files = {
      vtp("", kPointsTag + "\"ascii\">0 0 0 1 0 0 1 1 0 0 1 0</DataArray>"),
      vtp("", kPointsTag + "\"binary\">" + base64(word(data.size()) + data) + "</DataArray>"),
      vtp("", kPointsTag + "\"binary\">" + base64(word(data.size())) + base64(data) + "</DataArray>"),
      vtp(kZlib, kPointsTag + "\"binary\">\n  " + compressed_base64(data, data.size()) + "\n</DataArray>"),
      vtp("", kPointsTag + "\"appended\" offset=\"0\"/>", "", "", word(data.size()) + data),
  };
  for (const std::string& f : files) {
    INFO(f);
    const Mesh m = read(f);
    REQUIRE(m.face_count() == 1);
    REQUIRE(m.is_quad(0));
    REQUIRE(m.vertices.size() == 4);
    REQUIRE(m.vertices[2] == Vec3(1, 1, 0));
  }
}

TEST_CASE("vtk .vtp reader: every malformed class is refused in one line", "[mesh][vtp]") {
  const std::string data = doubles(kSquare);
  SECTION("truncated base64") {
    std::string text = base64(word(data.size()) + data);
    text.resize(text.size() - 2);
    require_refusal([&] { read(vtp("", kPointsTag + "\"binary\">" + text + "</DataArray>")); }, "f.vtp:5: ",
                    "DataArray: its base64 text ends inside a group of 4 characters (truncated)");
    // A character that is not base64.
    std::string bad = base64(word(data.size()) + data);
    bad[20] = '!';
    require_refusal([&] { read(vtp("", kPointsTag + "\"binary\">" + bad + "</DataArray>")); }, "f.vtp:5: ",
                    "DataArray: '!' in its base64 text is not a base64 character");
    // Whole groups, but fewer bytes than the header declares.
    require_refusal(
        [&] { read(vtp("", kPointsTag + "\"binary\">" + base64(word(data.size()) + data.substr(0, 48)) + "</DataArray>")); },
        "f.vtp:5: ", "its header declares 96 bytes, more than the");
  }
  SECTION("a block header larger than the data") {
    const std::string block = zlib(data);
    const std::string header = base64(word(1) + word(96) + word(96) + word(5000));
    require_refusal([&] { read(vtp(kZlib, kPointsTag + "\"binary\">" + header + base64(block) + "</DataArray>")); },
                    "f.vtp:5: ", "compressed block 0 of 5000 bytes, more than the file holds");
    require_refusal(
        [&] { read(vtp(kZlib, kPointsTag + "\"binary\">" + base64(word(1000000)) + "</DataArray>")); }, "f.vtp:5: ",
        "its header declares 1000000 compressed blocks, more than");
  }
  SECTION("a zip bomb") {
    // A block that inflates past its declared size is stopped there ...
    const std::string zeros(1 << 20, '\0');
    require_refusal([&] { read(vtp(kZlib, kPointsTag + "\"binary\">" + compressed_base64(zeros, 96) + "</DataArray>")); },
                    "f.vtp:5: ", "compressed block 0 inflates to more than its declared 96 bytes (a zip bomb");
    // ... and a declared size no zlib stream of its compressed size can hold is refused before anything inflates.
    const std::string x = zlib("x");
    const std::string big = base64(word(1) + word(100000000) + word(100000000) + word(x.size())) + base64(x);
    require_refusal([&] { read(vtp(kZlib, kPointsTag + "\"binary\">" + big + "</DataArray>")); }, "f.vtp:5: ",
                    "declares 100000000 bytes from " + std::to_string(x.size()) +
                        " compressed bytes, more than zlib's largest ratio of 1032");
  }
  SECTION("offsets out of range, a point id out of range") {
    const std::string points = kPointsTag + "\"ascii\">0 0 0 1 0 0 1 1 0 0 1 0</DataArray>";
    const std::string ids = "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0 1 2 3</DataArray>\n";
    require_refusal(
        [&] { read(vtp("", points, ids + "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">5</DataArray>\n")); },
        "f.vtp:9: ", "Polys offsets: offset 5 of cell 0 is not between the previous offset 0 and the connectivity's 4 ids");
    require_refusal(
        [&] {
          read(vtp("", points,
                   "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0 1 2 9</DataArray>\n"
                   "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">4</DataArray>\n"));
        },
        "f.vtp:8: ", "Polys connectivity: point id 9 of cell 0 is out of range (4 points)");
  }
  SECTION("an appended offset past the end") {
    require_refusal(
        [&] { read(vtp("", kPointsTag + "\"appended\" offset=\"1000\"/>", "", "", word(data.size()) + data)); },
        "f.vtp:5: ", "DataArray: offset 1000 is past the end of the appended data (");
    // Appended data cut short: the header declares more than the file holds after it.
    require_refusal(
        [&] { read(vtp("", kPointsTag + "\"appended\" offset=\"0\"/>", "", "", word(data.size()) + data.substr(0, 50))); },
        "f.vtp:5: ", "its header declares 96 bytes, more than the");
  }
  SECTION("a compressed String array with more strings than tuples") {
    // VTK 9.1 wrote past its array on this one (the open finding of the vtk fuzz harness).
    const std::string names = std::string("wall") + '\0' + "floor" + '\0';
    const std::string field = "<FieldData>\n<Array type=\"String\" Name=\"material_names\" NumberOfTuples=\"1\" "
                              "format=\"binary\">" + compressed_base64(names, names.size()) + "</Array>\n</FieldData>\n";
    const std::string points = kPointsTag + "\"binary\">" + compressed_base64(data, data.size()) + "</DataArray>";
    require_refusal([&] { read(vtp(kZlib, points, "", field)); }, "f.vtp:4: ",
                    "Array 'material_names': holds more strings than its 1 tuples");
  }
  SECTION("a compressor other than zlib") {
    require_refusal(
        [&] { read(vtp(" compressor=\"vtkLZ4DataCompressor\"", kPointsTag + "\"ascii\">0 0 0 1 0 0 1 1 0 0 1 0</DataArray>")); },
        "f.vtp:1: ", "compressor=\"vtkLZ4DataCompressor\": radwalk reads uncompressed and vtkZLibDataCompressor data only");
  }
  SECTION("XML that is not well formed, a DOCTYPE") {
    require_refusal([&] { read("<VTKFile type=\"PolyData\">\n<PolyData></Piece>"); }, "f.vtp:2: ",
                    "not well-formed XML: mismatched tag");
    require_refusal([&] { read("<?xml version=\"1.0\"?>\n<!DOCTYPE x [<!ENTITY a \"aaaa\">]>\n<VTKFile/>"); },
                    "f.vtp:2: ", "a DOCTYPE: a .vtp has none");
  }
}

namespace {

// Two quads sharing an edge, a triangle strip of two triangles and a vertex cell (ignored with a warning), with
// the cell data and name tables radwalk reads.
vtkNew<vtkPolyData> vtk_scene() {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (const auto& p : std::vector<std::array<double, 3>>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0},
                                                          {2, 1, 0}, {0, 0, 1}, {0.1, 0, 1}, {0, 0.1, 1}, {0.1, 0.1, 1}})
    points->InsertNextPoint(p.data());
  vtkNew<vtkCellArray> verts, polys, strips;
  const vtkIdType vert[] = {0}, quad0[] = {0, 1, 2, 3}, quad1[] = {1, 4, 5, 2}, strip[] = {6, 7, 8, 9};
  verts->InsertNextCell(1, vert);
  polys->InsertNextCell(4, quad0);
  polys->InsertNextCell(4, quad1);
  strips->InsertNextCell(4, strip);
  vtkNew<vtkPolyData> data;
  data->SetPoints(points);
  data->SetVerts(verts);
  data->SetPolys(polys);
  data->SetStrips(strips);
  // Cells in VTK's order: the vertex, the two polygons, the strip.
  vtkNew<vtkDoubleArray> rho, E;
  rho->SetName("rho");
  rho->SetNumberOfComponents(3);
  E->SetName("E");
  E->SetNumberOfComponents(3);
  vtkNew<vtkIntArray> material_id;
  material_id->SetName("material_id");
  // Values an ascii file holds exactly.
  const double rhos[4][3] = {{0, 0, 0}, {0.5, 0.25, 0.125}, {0.75, 0.75, 0.75}, {0.0625, 0.5, 0.25}};
  const double Es[4][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {4, 2, 1}};
  for (int c = 0; c < 4; ++c) {
    rho->InsertNextTuple(rhos[c]);
    E->InsertNextTuple(Es[c]);
    material_id->InsertNextValue(c == 0 ? 0 : c - 1);
  }
  data->GetCellData()->AddArray(rho);
  data->GetCellData()->AddArray(E);
  data->GetCellData()->AddArray(material_id);
  vtkNew<vtkStringArray> names;
  names->SetName("material_names");
  for (const char* n : {"floor", "wall", "lamp"}) names->InsertNextValue(n);
  data->GetFieldData()->AddArray(names);
  return data;
}

std::string vtk_written(vtkPolyData* data, const std::function<void(vtkXMLPolyDataWriter*)>& configure) {
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(data);
  writer->WriteToOutputStringOn();
  configure(writer);
  REQUIRE(writer->Write() == 1);
  return writer->GetOutputString();
}

}  // namespace

TEST_CASE("vtk .vtp reader: what vtkXMLPolyDataWriter writes reads as its ascii file does", "[mesh][vtp]") {
  vtkNew<vtkPolyData> data = vtk_scene();
  const Mesh ascii = read_vtk_polydata_bytes("vtk.vtp", vtk_written(data, [](vtkXMLPolyDataWriter* w) {
                                               w->SetDataModeToAscii();
                                             }),
                                             true);
  // The ascii file itself against the scene: 2 quads, 2 strip triangles facing +z, materials by name.
  REQUIRE(ascii.face_count() == 4);
  REQUIRE(ascii.is_quad(0));
  REQUIRE(ascii.is_quad(1));
  REQUIRE_FALSE(ascii.is_quad(2));
  REQUIRE(ascii.findings.size() == 1);  // the vertex cell, ignored
  REQUIRE(ascii.materials.size() == 3);
  REQUIRE(ascii.materials[static_cast<std::size_t>(ascii.face_material[0])].name == "floor");
  REQUIRE((ascii.materials[static_cast<std::size_t>(ascii.face_material[0])].Kd == Rgb(0.5, 0.25, 0.125)).all());
  REQUIRE(ascii.materials[static_cast<std::size_t>(ascii.face_material[1])].name == "wall");
  const Material& lamp = ascii.materials[static_cast<std::size_t>(ascii.face_material[2])];
  REQUIRE(lamp.name == "lamp");
  REQUIRE(lamp.Ke[0] == 4 / kPi);
  REQUIRE(ascii.face_material[3] == ascii.face_material[2]);

  const std::vector<std::pair<const char*, std::function<void(vtkXMLPolyDataWriter*)>>> modes = {
      {"binary, zlib", [](vtkXMLPolyDataWriter* w) { w->SetDataModeToBinary(); w->SetCompressorTypeToZLib(); }},
      {"binary, zlib, small blocks, UInt32 headers",
       [](vtkXMLPolyDataWriter* w) {
         w->SetDataModeToBinary();
         w->SetCompressorTypeToZLib();
         w->SetBlockSize(16);
         w->SetHeaderTypeToUInt32();
       }},
      {"binary, uncompressed", [](vtkXMLPolyDataWriter* w) { w->SetDataModeToBinary(); w->SetCompressorTypeToNone(); }},
      {"appended raw, zlib", [](vtkXMLPolyDataWriter* w) { w->SetDataModeToAppended(); w->EncodeAppendedDataOff(); }},
      {"appended raw, uncompressed, BigEndian",
       [](vtkXMLPolyDataWriter* w) {
         w->SetDataModeToAppended();
         w->EncodeAppendedDataOff();
         w->SetCompressorTypeToNone();
         w->SetByteOrderToBigEndian();
       }},
      {"appended base64, zlib", [](vtkXMLPolyDataWriter* w) { w->SetDataModeToAppended(); w->EncodeAppendedDataOn(); }},
      {"appended base64, uncompressed, UInt32 headers",
       [](vtkXMLPolyDataWriter* w) {
         w->SetDataModeToAppended();
         w->EncodeAppendedDataOn();
         w->SetCompressorTypeToNone();
         w->SetHeaderTypeToUInt32();
       }},
      {"binary, zlib, BigEndian",
       [](vtkXMLPolyDataWriter* w) {
         w->SetDataModeToBinary();
         w->SetCompressorTypeToZLib();
         w->SetByteOrderToBigEndian();
       }},
  };
  for (const auto& [what, configure] : modes) {
    INFO(what);
    const Mesh m = read_vtk_polydata_bytes("vtk.vtp", vtk_written(data, configure), true);
    REQUIRE(m.vertices == ascii.vertices);
    REQUIRE(m.faces == ascii.faces);
    REQUIRE(m.face_material == ascii.face_material);
    REQUIRE(m.materials.size() == ascii.materials.size());
    for (std::size_t k = 0; k < m.materials.size(); ++k) {
      REQUIRE(m.materials[k].name == ascii.materials[k].name);
      REQUIRE((m.materials[k].Kd == ascii.materials[k].Kd).all());
      REQUIRE((m.materials[k].Ke == ascii.materials[k].Ke).all());
    }
    REQUIRE(m.findings.size() == ascii.findings.size());
  }
}
