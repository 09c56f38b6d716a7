// The .vtp reads back through VTK's own reader with the same arrays, types, names, values and field data.
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationStringKey.h>
#include <vtkPointData.h>
#include <vtkStringArray.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "core/srgb.h"
#include "io/paraview_state.h"
#include "io/vtp_writer.h"
#include "patch/patch_builder.h"
#include "vtp_test_helpers.h"

using namespace radwalk;

static PatchSet two_patches() {
  PatchBuilder b;
  const int white = b.add_material("white", Rgb(0.73, 0.5, 0.25));
  const int light = b.add_material("light", Rgb(0.1, 0.2, 0.3), Rgb(1, 2, 3));
  b.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, white);
  b.add_triangle({0, 0, 1}, {0, 1, 1}, {1, 0, 1}, light);
  return b.build();
}

TEST_CASE("write_vtp: cell arrays read back with VTK's reader, with their types and component names", "[io][vtp]") {
  const PatchSet patches = two_patches();
  auto fields = patch_fields(patches);
  PatchRgb B(2, 3);
  B << 1.5, 2.5, 3.5, 4.5, 5.5, 200;
  fields.push_back(rgb_field("B", B));
  fields.push_back(scalar_field("rays", {1000, 2000}, FieldKind::count));

  const auto path = temp_file("radwalk_test.vtp");
  write_vtp(path, patches, fields);
  const auto poly = read_vtp(path);
  REQUIRE(poly->GetNumberOfCells() == 2);
  REQUIRE(poly->GetNumberOfPoints() == 7);
  vtkCellData* cells = poly->GetCellData();
  vtkPointData* points = poly->GetPointData();
  for (const char* name : {"patch", "face", "area", "normal", "rho", "E", "B", "B_rgb", "B_srgb", "rays"}) {
    INFO(name);
    REQUIRE(cells->GetArray(name) != nullptr);
  }
  // Ids and counts are integers, with no point field; geometry has no point field either.
  for (const char* name : {"patch", "face", "rays"}) {
    INFO(name);
    CHECK(cells->GetArray(name)->GetDataType() == VTK_LONG_LONG);
    CHECK(points->GetArray(name) == nullptr);
  }
  CHECK(cells->GetArray("rays")->GetComponent(1, 0) == 2000);
  CHECK(points->GetArray("area") == nullptr);
  CHECK(points->GetArray("normal") == nullptr);
  for (const char* name : {"rho", "E", "B_rgb", "B_srgb"}) {
    INFO(name);
    REQUIRE(points->GetArray(name) != nullptr);
    CHECK(std::string(cells->GetArray(name)->GetComponentName(0)) == "R");
    CHECK(std::string(cells->GetArray(name)->GetComponentName(1)) == "G");
    CHECK(std::string(cells->GetArray(name)->GetComponentName(2)) == "B");
    CHECK(std::string(points->GetArray(name)->GetComponentName(2)) == "B");
  }
  CHECK(cells->GetArray("normal")->GetComponentName(0) == nullptr);  // X, Y, Z
  // B is the active scalars, so ParaView colours by it on Apply.
  REQUIRE(cells->GetScalars() != nullptr);
  CHECK(std::string(cells->GetScalars()->GetName()) == "B");

  vtkDataArray* area = cells->GetArray("area");
  CHECK(area->GetComponent(0, 0) == Approx(1.0));
  CHECK(area->GetComponent(1, 0) == Approx(0.5));
  CHECK(cells->GetArray("rho")->GetComponent(0, 0) == 0.73);  // exact: doubles are stored as doubles
  CHECK(cells->GetArray("E")->GetComponent(1, 2) == Approx(3 * kPi));
  vtkDataArray* b = cells->GetArray("B_rgb");
  CHECK(b->GetNumberOfComponents() == 3);
  CHECK(b->GetComponent(1, 1) == 5.5);
  CHECK(cells->GetArray("normal")->GetComponent(0, 2) == Approx(1.0));
  CHECK(cells->GetArray("normal")->GetComponent(1, 2) == Approx(-1.0));
  // B_srgb: 8-bit sRGB of B / pi, clamped (200 / pi > 1 is full white, never wraps).
  vtkDataArray* srgb = cells->GetArray("B_srgb");
  CHECK(srgb->GetDataType() == VTK_UNSIGNED_CHAR);
  CHECK(srgb->GetComponent(0, 0) == srgb8_from_linear(1.5 / kPi));
  CHECK(srgb->GetComponent(1, 2) == 255);
  CHECK(int(srgb8_from_linear(1.5 / kPi)) == 184);  // 255 * (1.055 * 0.47746^(1/2.4) - 0.055) = 183.68
  // Point data: no point is shared here, so each point carries its patch's value.
  CHECK(points->GetArray("B_rgb")->GetComponent(0, 0) == Approx(1.5));
  CHECK(points->GetArray("B")->GetComponent(0, 0) == Approx(2.5));
  std::filesystem::remove(path);
}

TEST_CASE("write_vtp: the active scalar B is one component, the channel mean of the RGB radiosity", "[io][vtp]") {
  // What ParaView colours by on Apply must mean what its name says: for grey data the radiosity itself, not the
  // magnitude sqrt(3) B of the RGB triple.
  const PatchSet patches = two_patches();
  PatchRgb B(2, 3);
  B << 365, 365, 365, 1.0, 2.0, 6.0;
  const auto path = temp_file("radwalk_test_mean.vtp");
  write_vtp(path, patches, {rgb_field("B", B)});
  const auto poly = read_vtp(path);
  for (vtkDataSetAttributes* data : {static_cast<vtkDataSetAttributes*>(poly->GetCellData()),
                                     static_cast<vtkDataSetAttributes*>(poly->GetPointData())}) {
    vtkDataArray* mean = data->GetArray("B");
    REQUIRE(mean != nullptr);
    CHECK(mean->GetNumberOfComponents() == 1);
    vtkDataArray* rgb = data->GetArray("B_rgb");
    REQUIRE(rgb != nullptr);
    CHECK(rgb->GetNumberOfComponents() == 3);
    CHECK(std::string(rgb->GetComponentName(1)) == "G");
    for (vtkDataArray* a : {mean, rgb}) {  // the unit travels with the arrays
      INFO(a->GetName());
      REQUIRE(a->GetInformation()->Has(vtkDataArray::UNITS_LABEL()));
      CHECK(std::string(a->GetInformation()->Get(vtkDataArray::UNITS_LABEL())) == "W/unit^2");
    }
  }
  vtkDataArray* scalars = poly->GetCellData()->GetScalars();
  REQUIRE(scalars != nullptr);
  CHECK(std::string(scalars->GetName()) == "B");
  CHECK(scalars->GetComponent(0, 0) == 365.0);  // grey: B itself
  CHECK(scalars->GetComponent(1, 0) == 3.0);    // (1 + 2 + 6) / 3
  double range[2];
  scalars->GetRange(range, 0);
  CHECK(range[1] == 365.0);  // what ParaView's colour map spans
  // B_rgb and B_srgb are the writer's: a caller's own is refused beside B.
  CHECK_THROWS_AS(write_vtp(temp_file("radwalk_bad.vtp"), patches, {rgb_field("B", B), rgb_field("B_rgb", B)}),
                  std::logic_error);
  std::filesystem::remove(path);
}

TEST_CASE("write_vtp: field data carry the run metadata with their types", "[io][vtp]") {
  VtpMetadata m;
  m.set_text("command_line", "radwalk solve scene.obj --seed 7");
  m.set_real("residual", 1.5e-11);
  m.set_integer("seed", 7);
  m.set_integer("seed", 8);  // replaces
  const auto path = temp_file("radwalk_test_fd.vtp");
  write_vtp(path, two_patches(), {}, m);
  const auto poly = read_vtp(path);
  vtkFieldData* fd = poly->GetFieldData();
  REQUIRE(fd->GetNumberOfArrays() == 4);  // and the table material_names
  auto* text = vtkStringArray::SafeDownCast(fd->GetAbstractArray("command_line"));
  REQUIRE(text != nullptr);
  CHECK(text->GetValue(0) == "radwalk solve scene.obj --seed 7");
  REQUIRE(fd->GetArray("residual") != nullptr);
  CHECK(fd->GetArray("residual")->GetDataType() == VTK_DOUBLE);
  CHECK(fd->GetArray("residual")->GetComponent(0, 0) == 1.5e-11);
  CHECK(fd->GetArray("seed")->GetDataType() == VTK_LONG_LONG);
  CHECK(fd->GetArray("seed")->GetComponent(0, 0) == 8);
  std::filesystem::remove(path);
}

TEST_CASE("write_vtp refuses names ParaView's Calculator cannot use", "[io][vtp]") {
  const PatchSet p = two_patches();
  for (const char* name : {"var", "VAR", "if", "pi", "lambda", "mean_gather-absorption", "B se", "2B"}) {
    INFO(name);
    CHECK_THROWS_AS(write_vtp(temp_file("radwalk_bad.vtp"), p, {scalar_field(name, {1.0, 2.0})}), std::logic_error);
  }
  CHECK(paraview_name("mean_gather-expected-value") == "mean_gather_expected_value");
  for (const char* name : {"B", "E", "B_var", "rho", "patch", "mean_gather_absorption", "jump"}) {
    INFO(name);
    CHECK_FALSE(is_calculator_reserved(name));
  }
  CHECK(with_csv_name(rgb_field("B_var", PatchRgb::Zero(2, 3)), "var").column_name() == "var");
}

TEST_CASE("write_paraview_state: a Python state naming the data, the colouring and the camera", "[io][vtp]") {
  const auto path = temp_file("radwalk_state.py");
  StateColouring colouring;
  colouring.field = "B";
  colouring.title = "B [W/unit^2]";
  colouring.lo = 0.25;
  colouring.hi = 3.5;
  write_paraview_state(path, "results/cb.vtp", {Vec3(278, 273, -800), Vec3(278, 273, 0), Vec3(0, 1, 0), 39.3},
                       colouring);
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  CHECK(s.find("name = 'cb.vtp'") != std::string::npos);
  CHECK(s.find("field = 'B'") != std::string::npos);
  CHECK(s.find("title = 'B [W/unit^2]'") != std::string::npos);
  CHECK(s.find("value_range = [0.25, 3.5]") != std::string::npos);
  CHECK(s.find("ApplyPreset('Viridis (matplotlib)', True)") != std::string::npos);
  CHECK(s.find("AutomaticRescaleRangeMode = 'Never'") < s.find("RescaleTransferFunction(value_range[0]"));
  CHECK(s.find("SetScalarBarVisibility(view, True)") != std::string::npos);
  CHECK(s.find("display.Interpolation = 'Gouraud'") != std::string::npos);
  CHECK(s.find("UseColorPaletteForBackground = 0") != std::string::npos);
  CHECK(s.find("view.CameraPosition = [278, 273, -800]") != std::string::npos);
  CHECK(s.find("view.CameraViewAngle = 39.299999999999997") != std::string::npos);
  // The camera is set after the first render (which resets it).
  CHECK(s.find("simple.Render(view)") < s.find("view.CameraPosition"));
  std::filesystem::remove(path);
}

TEST_CASE("radiosity_colouring: the range of B's channel mean without the emitters", "[io][vtp]") {
  const PatchSet patches = two_patches();  // patch 0 white, patch 1 a light
  const StateColouring c = radiosity_colouring(patches, {1.0, 2.0, 6.0, 500, 600, 700});
  CHECK(c.field == "B");
  CHECK(c.title.find("W/") != std::string::npos);  // the unit is in the colour bar's title
  CHECK(c.lo == 3.0);
  CHECK(c.hi > 3.0);
  CHECK(c.hi < 3.0001);  // the light's 600 is left out; one value is widened to a range
  PatchBuilder b;
  const int light = b.add_material("light", Rgb(0.5, 0.5, 0.5), Rgb(1, 1, 1));
  b.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, light);
  b.add_quad({0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}, light);
  const StateColouring all = radiosity_colouring(b.build(), {1, 1, 1, 4, 4, 4});  // every patch emits
  CHECK(all.lo == 1.0);
  CHECK(all.hi == 4.0);
}

TEST_CASE("write_vtp on a full disk fails in one line and keeps the old file", "[io][vtp][fault]") {
  // C1: VTK 9.1's file writer segfaulted on a nearly full disk; D1: on a full disk it published an empty file over
  // the old one and exit 0. A real full disk: a 256 KiB tmpfs (skipped with a message where mounting is not
  // permitted).
  const auto mnt = std::filesystem::temp_directory_path() / ("radwalk_vtp_full_" + std::to_string(::getpid()));
  std::filesystem::create_directories(mnt);
  if (std::system(("mount -t tmpfs -o size=256k tmpfs " + mnt.string() + " 2>/dev/null").c_str()) != 0) {
    WARN("skipped: cannot mount a tmpfs here (needs root and mount permission)");
    return;
  }
  PatchBuilder small, big;
  const int m = small.add_material("wall", Rgb::Constant(0.5)), mb = big.add_material("wall", Rgb::Constant(0.5));
  small.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, m);
  // Enough patches that the compressed file cannot fit in what is left (random values do not compress).
  for (int i = 0; i < 40000; ++i) {
    const double x = i % 200, y = i / 200;
    big.add_quad({x, y, 0}, {x + 1, y, 0}, {x + 1, y + 1, 0}, {x, y + 1, 0}, mb);
  }
  const PatchSet a = small.build(), b = big.build();
  std::vector<double> noise(b.size());
  for (std::size_t i = 0; i < noise.size(); ++i) noise[i] = std::sin(1e4 * static_cast<double>(i));
  const std::string path = (mnt / "out.vtp").string();
  write_vtp(path, a, {});
  const auto before = std::filesystem::file_size(path);
  CHECK_THROWS_WITH(write_vtp(path, b, {scalar_field("noise", noise)}),
                    Catch::Contains("out.vtp") && Catch::Contains("disk full"));
  CHECK(std::filesystem::file_size(path) == before);
  CHECK(std::distance(std::filesystem::directory_iterator(mnt), std::filesystem::directory_iterator()) == 1);
  std::system(("umount " + mnt.string()).c_str());
}

TEST_CASE("write_vtp: each cell's object, group and material as ids into field data string tables", "[io][vtp]") {
  PatchSet patches = two_patches();
  // Input face 0 in object 'chair', group 'seat'; input face 1 in a group 'leg' of no object.
  patches.input_face_group = {0, 1};
  patches.group_object = {"chair", ""};
  patches.group_name = {"seat", "leg"};
  const auto path = temp_file("radwalk_test_names.vtp");
  write_vtp(path, patches, {});
  const auto poly = read_vtp(path);
  auto table = [&](const char* name) {
    auto* a = vtkStringArray::SafeDownCast(poly->GetFieldData()->GetAbstractArray(name));
    REQUIRE(a != nullptr);
    std::vector<std::string> v;
    for (vtkIdType k = 0; k < a->GetNumberOfValues(); ++k) v.push_back(a->GetValue(k));
    return v;
  };
  auto ids = [&](const char* name) {
    vtkDataArray* a = poly->GetCellData()->GetArray(name);
    REQUIRE(a != nullptr);
    REQUIRE(a->GetNumberOfTuples() == 2);
    return std::vector<double>{a->GetComponent(0, 0), a->GetComponent(1, 0)};
  };
  CHECK(table("object_names") == std::vector<std::string>{"chair"});
  CHECK(table("group_names") == std::vector<std::string>{"seat", "leg"});
  CHECK(table("material_names") == std::vector<std::string>{"white", "light"});
  CHECK(ids("object_id") == std::vector<double>{0, -1});
  CHECK(ids("group_id") == std::vector<double>{0, 1});
  CHECK(ids("material_id") == std::vector<double>{0, 1});
  std::filesystem::remove(path);
}
