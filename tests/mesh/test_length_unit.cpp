// The length unit after --scale, as --unit names the file's (mesh/length_unit.h): the summaries' names of the
// unit of lengths and of B.
#include <catch2/catch.hpp>

#include "mesh/length_unit.h"

using namespace radwalk;

TEST_CASE("the unit of lengths and of B after --unit and --scale", "[mesh][units]") {
  auto unit = [](const char* file, double scale) {
    LengthUnit u;
    u.file_unit = file;
    u.scale = scale;
    return u;
  };
  CHECK(unit("", 1).length() == "mesh unit");
  CHECK(unit("", 1).radiosity() == "W per mesh unit^2");
  CHECK(unit("mm", 1).length() == "mm");
  CHECK(unit("mm", 1).radiosity() == "W/mm^2");
  CHECK(unit("mm", 0.001).length() == "m");
  CHECK(unit("mm", 0.001).radiosity() == "W/m^2");
  CHECK(unit("cm", 0.01).length() == "m");
  CHECK(unit("cm", 10).length() == "mm");
  CHECK(unit("in", 0.0254).length() == "m");
  CHECK(unit("ft", 12).length() == "in");
  CHECK(unit("mm", 2).length() == "0.5 mm");
  CHECK(unit("mm", 2).radiosity() == "W/(0.5 mm)^2");
  CHECK(unit("", 0.01).length() == "100 mesh unit");
  CHECK(metres_per("ft") == 0.3048);
  CHECK(metres_per("yd") == 0);
  Mesh mesh;
  mesh.vertices = {{1, 2, 3}};
  scale_mesh(mesh, 0.5);
  CHECK(mesh.vertices[0] == Vec3(0.5, 1, 1.5));
}
