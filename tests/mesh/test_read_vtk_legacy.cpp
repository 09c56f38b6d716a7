// radwalk's own legacy .vtk reader (mesh/vtk_legacy.h, through read_vtk_polydata_bytes): the same square in every
// layout and encoding, what VTK's own legacy writer writes (ASCII and BINARY, file versions 4.2 and 5.1) against the
// data it wrote, the reproducers of the crashes the vtk fuzz harness found in VTK 9.1's legacy reader, and the
// malformed classes (truncated data, oversized counts) each refused in one line naming the file and the place.
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkPolyDataWriter.h>
#include <vtkStringArray.h>
#include <vtkUnsignedCharArray.h>

#include "core/error.h"
#include "mesh/read_vtk.h"
#include "mesh/vtk_legacy.h"

using namespace radwalk;

namespace {

template <class Body>
void require_refusal(Body&& body, const std::string& where, const std::string& words) {
  try {
    body();
    FAIL("accepted; expected a refusal with '" << words << "'");
  } catch (const InputError& e) {
    const std::string m = e.what();
    INFO(m);
    REQUIRE(m.rfind(where, 0) == 0);
    REQUIRE(m.find('\n') == std::string::npos);
    REQUIRE(m.find(words) != std::string::npos);
  }
}

// Big-endian bytes of a value, as the BINARY legacy format stores it.
template <class T>
std::string be(T value) {
  char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  return std::string(std::rbegin(b), std::rend(b));
}
template <class T>
std::string be_all(std::initializer_list<T> values) {
  std::string s;
  for (T v : values) s += be(v);
  return s;
}

// The square (4 points) as a quad, a triangle strip of the same 4 points (2 triangles) and a vertex cell; cell
// data rho (double, 3), E (float, 3, a second SCALARS), material_id (FIELD, int); field data material_names.
// `binary` and `version5` pick the encoding and the cell layout.
std::string square(bool binary, bool version5) {
  std::string s = std::string("# vtk DataFile Version ") + (version5 ? "5.1" : "3.0") + "\nsquare\n" +
                  (binary ? "BINARY" : "ASCII") + "\nDATASET POLYDATA\n";
  s += "FIELD FieldData 1\nmaterial_names 1 2 string\n";
  if (binary)
    s += std::string("\xcb") + "white pa" + "int" + std::string("\xc4") + "lamp\n";  // 0b11 + length 11, 4
  else
    s += "white%20paint\nlamp\n";
  s += std::string("POINTS 4 ") + (binary ? "float\n" + be_all<float>({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}) + "\n"
                                          : "double\n0 0 0 1 0 0\n1 1 0 0 1 0\n");
  // Cells: a vertex, the quad, the strip.
  struct Cells {
    const char* key;
    std::vector<std::vector<std::int32_t>> cells;
  };
  for (const Cells& c : {Cells{"VERTICES", {{0}}}, Cells{"POLYGONS", {{0, 1, 2, 3}}}, Cells{"TRIANGLE_STRIPS", {{0, 1, 3, 2}}}}) {
    std::vector<std::int64_t> offsets{0}, ids, legacy;
    for (const auto& cell : c.cells) {
      legacy.push_back(static_cast<std::int64_t>(cell.size()));
      for (std::int32_t id : cell) {
        ids.push_back(id);
        legacy.push_back(id);
      }
      offsets.push_back(static_cast<std::int64_t>(ids.size()));
    }
    auto text = [](const std::vector<std::int64_t>& v) {
      std::string t;
      for (auto x : v) t += std::to_string(x) + " ";
      return t + "\n";
    };
    auto bytes32 = [](const std::vector<std::int64_t>& v) {
      std::string t;
      for (auto x : v) t += be(static_cast<std::int32_t>(x));
      return t + "\n";
    };
    auto bytes64 = [](const std::vector<std::int64_t>& v) {
      std::string t;
      for (auto x : v) t += be(static_cast<std::int64_t>(x));
      return t + "\n";
    };
    if (version5) {
      s += std::string(c.key) + " " + std::to_string(offsets.size()) + " " + std::to_string(ids.size()) + "\n";
      s += "OFFSETS vtktypeint64\n" + (binary ? bytes64(offsets) : text(offsets));
      s += "CONNECTIVITY vtktypeint64\n" + (binary ? bytes64(ids) : text(ids));
    } else {
      s += std::string(c.key) + " " + std::to_string(c.cells.size()) + " " + std::to_string(legacy.size()) + "\n";
      s += binary ? bytes32(legacy) : text(legacy);
    }
  }
  s += "CELL_DATA 3\nSCALARS rho double 3\nLOOKUP_TABLE default\n";
  s += binary ? be_all<double>({0, 0, 0, 0.5, 0.25, 0.125, 0.75, 0.75, 0.75}) + "\n"
              : "0 0 0\n0.5 0.25 0.125\n0.75 0.75 0.75\n";
  s += "SCALARS E float 3\nLOOKUP_TABLE default\n";
  s += binary ? be_all<float>({0, 0, 0, 0, 0, 0, 3, 6, 9}) + "\n" : "0 0 0 0 0 0 3 6 9\n";
  s += "FIELD FieldData 1\nmaterial_id 1 3 int\n";
  s += binary ? be_all<std::int32_t>({0, 0, 1}) + "\n" : "0 0 1\n";
  s += "POINT_DATA 4\nNORMALS n float\n";
  s += binary ? be_all<float>({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}) + "\n" : "0 0 1 0 0 1 0 0 1 0 0 1\n";
  return s;
}

// A vtkPolyData holding what radwalk reads from a legacy file, and more: every kind of cell, the cell data arrays
// radwalk uses in several types, arrays it does not use (strings, point data), field data tables with names that
// need escaping.
vtkSmartPointer<vtkPolyData> reference_polydata() {
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  const double xyz[][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 1.5, 0.1}, {2, 0, 0.25}, {2, 1, 1.0 / 3}};
  for (const auto& p : xyz) points->InsertNextPoint(p);
  pd->SetPoints(points);
  vtkNew<vtkCellArray> verts, lines, polys, strips;
  const vtkIdType v[] = {4};
  verts->InsertNextCell(1, v);
  const vtkIdType l[] = {0, 5};
  lines->InsertNextCell(2, l);
  const vtkIdType quad[] = {0, 1, 2, 3}, pentagon[] = {0, 1, 2, 4, 3}, triangle[] = {1, 5, 6};
  polys->InsertNextCell(4, quad);
  polys->InsertNextCell(5, pentagon);
  polys->InsertNextCell(3, triangle);
  const vtkIdType strip[] = {1, 5, 2, 6};
  strips->InsertNextCell(4, strip);
  pd->SetVerts(verts);
  pd->SetLines(lines);
  pd->SetPolys(polys);
  pd->SetStrips(strips);
  const int cells = 6;
  vtkNew<vtkDoubleArray> rho;
  rho->SetName("rho");
  rho->SetNumberOfComponents(3);
  vtkNew<vtkFloatArray> E;
  E->SetName("E");
  E->SetNumberOfComponents(3);
  vtkNew<vtkIntArray> material;
  material->SetName("material_id");
  vtkNew<vtkIdTypeArray> group;
  group->SetName("group_id");
  vtkNew<vtkUnsignedCharArray> side;
  side->SetName("side");
  vtkNew<vtkStringArray> label;
  label->SetName("label text");
  for (int c = 0; c < cells; ++c) {
    rho->InsertNextTuple3(0.1 * c, 0.3, 1.0 / 3);
    E->InsertNextTuple3(c == 3 ? 12.5 : 0, c == 3 ? 1.0 / 7 : 0, 0);
    material->InsertNextValue(c % 2);
    group->InsertNextValue(c / 3);
    side->InsertNextValue(0);
    label->InsertNextValue("cell " + std::to_string(c) + " 100%");
  }
  pd->GetCellData()->SetScalars(rho);
  pd->GetCellData()->AddArray(E);
  pd->GetCellData()->AddArray(material);
  pd->GetCellData()->AddArray(group);
  pd->GetCellData()->AddArray(side);
  pd->GetCellData()->AddArray(label);
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  for (int p = 0; p < 7; ++p) normals->InsertNextTuple3(0, 0, 1);
  pd->GetPointData()->SetNormals(normals);
  vtkNew<vtkStringArray> names;
  names->SetName("material_names");
  names->InsertNextValue("white paint");
  names->InsertNextValue("lamp 50% \"warm\"");
  vtkNew<vtkStringArray> groups;
  groups->SetName("group_names");
  groups->InsertNextValue("walls");
  groups->InsertNextValue("table");
  vtkNew<vtkDoubleArray> area;
  area->SetName("total_area");
  area->InsertNextValue(4.5);
  pd->GetFieldData()->AddArray(names);
  pd->GetFieldData()->AddArray(groups);
  pd->GetFieldData()->AddArray(area);
  return pd;
}

LegacyWanted radwalk_wanted() {
  LegacyWanted w;
  w.cell_arrays = {{"rho", 3}, {"E", 3}, {"side", 1}, {"material_id", 1}, {"group_id", 1}, {"object_id", 1}};
  w.field_strings = {"material_names", "group_names", "object_names"};
  return w;
}

void require_cells(const LegacyCells& read, vtkCellArray* original) {
  REQUIRE(static_cast<vtkIdType>(read.count()) == original->GetNumberOfCells());
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < original->GetNumberOfCells(); ++c) {
    original->GetCellAtId(c, ids);
    REQUIRE(read.offsets[static_cast<std::size_t>(c + 1)] - read.offsets[static_cast<std::size_t>(c)] ==
            ids->GetNumberOfIds());
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
      REQUIRE(read.ids[static_cast<std::size_t>(read.offsets[static_cast<std::size_t>(c)] + k)] == ids->GetId(k));
  }
}

std::string source_file(const std::string& relative) {
  std::ifstream in(std::string(RADWALK_SOURCE_DIR) + "/" + relative, std::ios::binary);
  REQUIRE(in.good());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("vtk .vtk reader: the square in every layout and encoding", "[mesh][vtk]") {
  const Mesh reference = read_vtk_polydata_bytes("ascii3.vtk", square(false, false), false);
  REQUIRE(reference.face_count() == 3);  // the quad and the strip's 2 triangles; the vertex cell is ignored
  REQUIRE(reference.findings.size() == 1);  // the warning about the vertex cell
  REQUIRE(reference.materials.size() == 2);
  const Material& paint = reference.materials[static_cast<std::size_t>(reference.face_material[0])];
  const Material& lamp = reference.materials[static_cast<std::size_t>(reference.face_material[1])];
  REQUIRE(paint.name == "white paint");  // %20 decoded
  REQUIRE((paint.Kd == Rgb(0.5, 0.25, 0.125)).all());
  REQUIRE((paint.Ke == Rgb::Zero()).all());
  REQUIRE(lamp.name == "lamp");
  REQUIRE((lamp.Kd == Rgb(0.75, 0.75, 0.75)).all());
  // E from a second SCALARS section (VTK's reader kept only the first SCALARS of a section and dropped it).
  REQUIRE((lamp.Ke == Rgb(3, 6, 9) / kPi).all());
  for (const bool binary : {false, true})
    for (const bool version5 : {false, true}) {
      INFO((binary ? "BINARY" : "ASCII") << (version5 ? " 5.1" : " 3.0"));
      const Mesh m = read_vtk_polydata_bytes("square.vtk", square(binary, version5), false);
      REQUIRE(m.vertices == reference.vertices);
      REQUIRE(m.faces == reference.faces);
      REQUIRE(m.face_material == reference.face_material);
      REQUIRE(m.materials.size() == reference.materials.size());
      for (std::size_t k = 0; k < m.materials.size(); ++k) {
        REQUIRE(m.materials[k].name == reference.materials[k].name);
        REQUIRE((m.materials[k].Kd == reference.materials[k].Kd).all());
        REQUIRE((m.materials[k].Ke == reference.materials[k].Ke).all());
      }
    }
}

TEST_CASE("vtk .vtk reader: what vtkPolyDataWriter writes reads as VTK's reader reads it", "[mesh][vtk]") {
  // VTK's writer in every encoding and cell layout; VTK's reader (every SCALARS, VECTORS, ... kept) is the reference
  // parse of the same bytes (ASCII rounds the numbers it writes, so the data written is the reference in BINARY
  // only, where both must agree with it exactly).
  const vtkSmartPointer<vtkPolyData> pd = reference_polydata();
  for (const int version : {42, 51})
    for (const bool binary : {false, true}) {
      INFO("version " << version << (binary ? " BINARY" : " ASCII"));
      vtkNew<vtkPolyDataWriter> writer;
      writer->SetInputData(pd);
      writer->WriteToOutputStringOn();
      writer->SetFileVersion(version);
      if (binary) writer->SetFileTypeToBinary();
      REQUIRE(writer->Write() == 1);
      const std::string bytes = writer->GetOutputStdString();
      vtkNew<vtkPolyDataReader> reader;
      reader->ReadFromInputStringOn();
      reader->SetBinaryInputString(bytes.data(), static_cast<int>(bytes.size()));
      reader->ReadAllScalarsOn();
      reader->ReadAllVectorsOn();
      reader->ReadAllNormalsOn();
      reader->ReadAllFieldsOn();
      reader->Update();
      vtkPolyData* vtk_read = reader->GetOutput();
      const LegacyPolyData read = parse_vtk_legacy("written.vtk", bytes, radwalk_wanted());
      for (vtkPolyData* reference : {vtk_read, binary ? pd.Get() : vtk_read}) {
        REQUIRE(static_cast<vtkIdType>(read.points.size()) == reference->GetNumberOfPoints());
        for (vtkIdType p = 0; p < reference->GetNumberOfPoints(); ++p) {
          double x[3];
          reference->GetPoint(p, x);
          REQUIRE(read.points[static_cast<std::size_t>(p)] == Vec3(x[0], x[1], x[2]));
        }
        require_cells(read.verts, reference->GetVerts());
        require_cells(read.lines, reference->GetLines());
        require_cells(read.polys, reference->GetPolys());
        require_cells(read.strips, reference->GetStrips());
        for (const char* name : {"rho", "E", "material_id", "group_id", "side"}) {
          INFO(name);
          vtkDataArray* a = reference->GetCellData()->GetArray(name);
          REQUIRE(a != nullptr);
          REQUIRE(read.cell_data.count(name) == 1);
          const std::vector<double>& values = read.cell_data.at(name);
          REQUIRE(static_cast<vtkIdType>(values.size()) == a->GetNumberOfValues());
          for (vtkIdType k = 0; k < a->GetNumberOfValues(); ++k)
            REQUIRE(values[static_cast<std::size_t>(k)] ==
                    a->GetComponent(k / a->GetNumberOfComponents(), static_cast<int>(k % a->GetNumberOfComponents())));
        }
      }
      REQUIRE(read.cell_data.count("object_id") == 0);
      REQUIRE(read.field_strings.at("material_names") == std::vector<std::string>{"white paint", "lamp 50% \"warm\""});
      REQUIRE(read.field_strings.at("group_names") == std::vector<std::string>{"walls", "table"});
      // And as a mesh: the quad, the pentagon's 3 triangles, the triangle and the strip's 2 triangles.
      const Mesh m = read_vtk_polydata_bytes("written.vtk", bytes, false);
      REQUIRE(m.face_count() == 7);
    }
}

TEST_CASE("vtk .vtk reader: the crashes found in VTK 9.1's legacy reader are refused in one line", "[mesh][vtk]") {
  // The reproducers of tests/fuzz/corpus/vtk: VTK 9.1 dereferenced a null pointer after a POINTS type matched by its
  // prefix ("stringdouble"), after a polygon index of 2^31 (its 32-bit read failed), after a word among a polygon's
  // indices; and read a stream it had closed after keywords matched by their prefix.
  const struct {
    const char* file;
    const char* place;
    const char* words;
  } cases[] = {
      {"regression-points-of-string-type.vtk", "f.vtk:5:", "POINTS of type 'stringdouble': not one of VTK's numeric types"},
      {"regression-cell-id-above-int32.vtk", "f.vtk:11:", "'POLYGONS2' is not a POLYDATA section"},
      {"regression-word-among-polygon-indices.vtk", "f.vtk:12:", "POLYGONS (line 11): 'float' is not a whole number"},
      {"regression-keyword-prefix.vtk", "f.vtk:11:", "'POLYGONS`1' is not a POLYDATA section"},
      {"regression-ascii-word-prefix.vtk", "f.vtk:3:", "where ASCII or BINARY belongs"},
      {"regression-tokens-outlive-lines.vtk", "f.vtk:4:", "where DATASET POLYDATA belongs"},
      {"regression-bad-field-array.vtk", "f.vtk:", "FIELD"},
  };
  for (const auto& c : cases) {
    INFO(c.file);
    const std::string bytes = source_file(std::string("tests/fuzz/corpus/vtk/") + c.file);
    require_refusal([&] { read_vtk_polydata_bytes("f.vtk", bytes, false); }, c.place, c.words);
  }
  // The same with 2^31 where it belongs (a polygon's last index).
  require_refusal(
      [&] {
        read_vtk_polydata_bytes("wide.vtk",
                                "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 4 float\n"
                                "0 0 0 1 0 0 1 1 0 0 1 0\nPOLYGONS 1 5\n4 0 1 2 2147483648\n",
                                false);
      },
      "wide.vtk:8:", "POLYGONS (line 7): '2147483648' is not a whole number from 0 to 2147483647");
}

TEST_CASE("vtk .vtk reader: truncated files, oversized counts and bad cells are refused in one line", "[mesh][vtk]") {
  const std::string head = "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\n";
  const std::string bhead = "# vtk DataFile Version 3.0\nx\nBINARY\nDATASET POLYDATA\n";
  const std::string head5 = "# vtk DataFile Version 5.1\nx\nASCII\nDATASET POLYDATA\n";
  const std::string points = "POINTS 4 float\n0 0 0 1 0 0 1 1 0 0 1 0\n";
  const std::string bpoints = "POINTS 4 float\n" + be_all<float>({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}) + "\n";
  const struct {
    const char* what;
    std::string bytes;
    const char* place;
    const char* words;
  } cases[] = {
      {"not a legacy file", "solid x\n", "c.vtk:1:", "not a legacy VTK file"},
      {"no title", "# vtk DataFile Version 3.0", "c.vtk:1:", "ends before its title"},
      {"an unstructured grid", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET UNSTRUCTURED_GRID\n", "c.vtk:4:",
       "radwalk reads legacy POLYDATA only"},
      {"a point count above the file", head + "POINTS 4000000000 float\n", "c.vtk:5:", "more than its remaining"},
      {"a binary point count above the file", bhead + "POINTS 100 double\n" + be_all<double>({0, 0, 0}), "c.vtk:5:",
       "POINTS declares 100 points, more than its remaining 32 bytes can hold"},
      {"a binary block cut short", bhead + "POINTS 4 float\n" + be_all<float>({0, 0, 0, 1, 0, 0, 1, 1}), "c.vtk:5:",
       "more than the 33 bytes left"},
      {"a short ascii points section", head + "POINTS 4 float\n0 0 0 1 0 0 1 1 0 0 1\n", "c.vtk:5:",
       "POINTS (line 5) ends before its 12 values"},
      {"a cell count above the file", head + points + "POLYGONS 5 2000000000\n", "c.vtk:7:", "more than its remaining"},
      {"a binary cell size above the file", bhead + bpoints + "POLYGONS 1 50\n" + be_all<std::int32_t>({4, 0, 1, 2, 3}),
       "c.vtk: at byte 117:", "POLYGONS declares 50 indices, more than its remaining 21 bytes"},
      {"a cell past its section", head + points + "POLYGONS 1 5\n7 0 1 2 3\n", "c.vtk:7:",
       "cell 0 of 7 points runs past the section's 5 indices"},
      {"a declared cell count that is not the cells", head + points + "POLYGONS 2 5\n4 0 1 2 3\n", "c.vtk:7:",
       "declares 2 cells, but its 5 indices hold 1"},
      {"a negative binary index", bhead + bpoints + "POLYGONS 1 5\n" + be_all<std::int32_t>({4, 0, 1, -2, 3}), "c.vtk: at byte",
       "(-2) is not from 0 to 2147483647"},
      {"a point id out of range", head + points + "POLYGONS 1 5\n4 0 1 2 4\n", "c.vtk:7:",
       "POLYGONS: cell 0: point id 4 is out of range (4 points)"},
      {"offsets that fall", head5 + points + "POLYGONS 3 4\nOFFSETS vtktypeint64\n0 3 2\nCONNECTIVITY vtktypeint64\n0 1 2 3\n",
       "c.vtk:7:", "offset 2 of cell 1 is not between the previous offset 3"},
      {"offsets that end early", head5 + points + "POLYGONS 2 4\nOFFSETS vtktypeint64\n0 3\nCONNECTIVITY vtktypeint64\n0 1 2 3\n",
       "c.vtk:7:", "OFFSETS end at 3, not at the connectivity's 4 ids"},
      {"a version 5 file in the classic layout", head5 + points + "POLYGONS 1 5\n4 0 1 2 3\n", "c.vtk:8:",
       "where OFFSETS belongs"},
      {"float offsets", head5 + points + "POLYGONS 2 4\nOFFSETS float\n0 4\nCONNECTIVITY int\n0 1 2 3\n", "c.vtk:8:",
       "cell arrays hold whole numbers"},
      {"a cell data count that is not the cells", head + points + "POLYGONS 1 5\n4 0 1 2 3\nCELL_DATA 2\n", "c.vtk:9:",
       "CELL_DATA 2: the file has 1 cells"},
      {"a string longer than the file", bhead + "FIELD FieldData 1\nmaterial_names 1 1 string\n" + be(std::uint16_t{0x8000 | 900}) + "ab",
       "c.vtk: at byte", "string 0 of 900 bytes, more than the 2 bytes left"},
      {"a field array count above the file", head + "FIELD FieldData 999999999\n", "c.vtk:5:", "999999999 arrays, more than"},
      {"a field array above the file", head + "FIELD FieldData 1\nrho 3 99999999 double\n", "c.vtk:6:",
       "declares 299999997 values of type double"},
      {"an unknown array type", head + points + "POLYGONS 1 5\n4 0 1 2 3\nCELL_DATA 1\nSCALARS rho float28 3\nLOOKUP_TABLE default\n1 1 1\n",
       "c.vtk:10:", "of type 'float28': not one of VTK's legacy types"},
      // VTK 9.1's reader only warned about a short ASCII array and kept it, its last values undefined.
      {"a short rho array", head + points + "POLYGONS 1 5\n4 0 1 2 3\nCELL_DATA 1\nSCALARS rho float 3\nLOOKUP_TABLE default\n"
       "0.5 0.5\n", "c.vtk:10:", "SCALARS 'rho' (line 10) ends before its 3 values"},
      {"rho given twice", head + points + "POLYGONS 1 5\n4 0 1 2 3\nCELL_DATA 1\nSCALARS rho float 3\nLOOKUP_TABLE default\n"
       "1 1 1\nVECTORS rho float\n0 0 0\n", "c.vtk:13:", "cell data 'rho' given twice"},
      {"POINTS given twice", head + points + points, "c.vtk:7:", "POINTS given twice (first on line 5)"},
      {"a non-finite point", bhead + "POINTS 1 float\n" + be(std::uint32_t{0x7fc00000}) + be_all<float>({0, 0}) + "\n", "c.vtk:5:",
       "point 0 is not finite"},
      {"an unknown attribute", head + points + "POLYGONS 1 5\n4 0 1 2 3\nCELL_DATA 1\nEDGE_FLAGS e int\n1\n", "c.vtk:10:",
       "'EDGE_FLAGS' is not a CELL_DATA attribute"},
  };
  for (const auto& c : cases) {
    INFO(c.what);
    require_refusal([&] { read_vtk_polydata_bytes("c.vtk", c.bytes, false); }, c.place, c.words);
  }
}
