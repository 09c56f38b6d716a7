// Point fields of the .vtp are smoothed per smoothing group (patch/display_mesh.h): never across a crease, a
// material or an emitter's edge, and without cracks or spikes at the T-junctions adaptive refinement leaves.
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkPointData.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <map>

#include "io/vtp_writer.h"
#include "patch/display_mesh.h"
#include "patch/patch_builder.h"
#include "patch/refine.h"
#include "vtp_test_helpers.h"

using namespace radwalk;

namespace {

// n x n unit quads on the plane through `origin` spanned by u and v (normal u x v).
void add_grid(PatchBuilder& b, const Vec3& origin, const Vec3& u, const Vec3& v, int n, int material,
              int special = -1, int special_material = -1) {
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec3 o = origin + i * u + j * v;
      b.add_quad(o, o + u, o + u + v, o + v, j * n + i == special ? special_material : material);
    }
}

// Two unit-high quads side by side on z = 0 sharing the edge x = 1: [0, 1] and [1, 1 + width], welded.
PatchSet side_by_side(double width) {
  PatchBuilder b;
  const int m = b.add_material("white", Rgb(0.5, 0.5, 0.5));
  b.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, m);
  b.add_quad({1, 0, 0}, {1 + width, 0, 0}, {1 + width, 1, 0}, {1, 1, 0}, m);
  PatchSet p = b.build();
  weld_points(p);
  return p;
}

// Per-patch values written as the quantity "x"; returns the file read back.
vtkSmartPointer<vtkPolyData> write_and_read(const PatchSet& p, const std::vector<double>& x, const std::string& name) {
  const auto path = temp_file(name);
  write_vtp(path, p, {scalar_field("x", x)});
  auto poly = read_vtp(path);
  std::filesystem::remove(path);
  return poly;
}

// The point values of cell i's polygon.
std::vector<double> cell_point_values(vtkPolyData* poly, vtkIdType i) {
  vtkNew<vtkIdList> ids;
  poly->GetCellPoints(i, ids);
  std::vector<double> v;
  for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    v.push_back(poly->GetPointData()->GetArray("x")->GetComponent(ids->GetId(k), 0));
  return v;
}

}  // namespace

TEST_CASE("point fields: a shared point within one plane carries the area-weighted average", "[io][vtp]") {
  const PatchSet p = side_by_side(2);
  const auto poly = write_and_read(p, {1.0, 4.0}, "radwalk_smooth_shared.vtp");
  REQUIRE(poly->GetNumberOfPoints() == 6);  // one plane, one group: nothing split
  const auto v = cell_point_values(poly, 0);  // corners (0,0), (1,0), (1,1), (0,1)
  CHECK(v[0] == 1.0);
  CHECK(v[1] == Approx((1.0 * 1 + 2.0 * 4) / 3.0));
  CHECK(v[2] == Approx((1.0 * 1 + 2.0 * 4) / 3.0));
}

TEST_CASE("point fields: two walls meeting at a corner keep their own values on each side", "[io][vtp]") {
  PatchBuilder b;
  const int m = b.add_material("white", Rgb(0.5, 0.5, 0.5));
  add_grid(b, {0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 2, m);  // floor y = 0, normal +y
  add_grid(b, {0, 0, 2}, {1, 0, 0}, {0, 1, 0}, 2, m);  // back wall z = 2, normal -z... shares the edge z = 2, y = 0
  PatchSet p = b.build();
  weld_points(p);
  REQUIRE(p.points.size() == 15);  // 9 + 9 less the 3 of the shared edge
  const std::vector<double> x = {1, 2, 3, 4, 10, 20, 30, 40};
  const auto poly = write_and_read(p, x, "radwalk_smooth_corner.vtp");
  CHECK(poly->GetNumberOfPoints() == 18);  // the crease's points are split
  for (vtkIdType i = 0; i < 8; ++i) {
    const double lo = i < 4 ? 1 : 10, hi = i < 4 ? 4 : 40;
    for (const double v : cell_point_values(poly, i)) {
      INFO("cell " << i << ": point value " << v);
      CHECK(v >= lo);
      CHECK(v <= hi);
    }
  }
}

TEST_CASE("point fields: a light set into a ceiling leaves no halo and keeps its own edge", "[io][vtp]") {
  PatchBuilder b;
  const int white = b.add_material("white", Rgb(0.5, 0.5, 0.5));
  const int light = b.add_material("light", Rgb(0.5, 0.5, 0.5), Rgb(10, 10, 10));
  add_grid(b, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}, 3, white, 4, light);  // ceiling y = 1, the centre patch emits
  PatchSet p = b.build();
  weld_points(p);
  std::vector<double> x(9, 1.0);
  x[4] = 50;
  const auto poly = write_and_read(p, x, "radwalk_smooth_light.vtp");
  CHECK(poly->GetNumberOfPoints() == 16 + 4);  // the light's 4 corners twice
  for (vtkIdType i = 0; i < 9; ++i)
    for (const double v : cell_point_values(poly, i)) {
      INFO("cell " << i);
      CHECK(v == (i == 4 ? 50.0 : 1.0));
    }
}

TEST_CASE("point fields: a T-junction from refinement is conforming, without cracks or spikes", "[io][vtp]") {
  const PatchSet p = split_patches(side_by_side(1), {false, true});  // patch 0 now has the T-junction (1, 0.5) on its edge
  REQUIRE(p.size() == 5);
  const std::vector<double> x = {1, 2, 3, 5, 8};
  const auto poly = write_and_read(p, x, "radwalk_smooth_t.vtp");

  // The unsplit patch's polygon lists the junction point: 5 corners, and its area is unchanged.
  vtkNew<vtkIdList> ids;
  poly->GetCellPoints(0, ids);
  REQUIRE(ids->GetNumberOfIds() == 5);
  const DisplayMesh mesh = make_display_mesh(p);
  CHECK(mesh.groups == 1);
  vtkIdType junction = -1;
  for (vtkIdType k = 0; k < 5; ++k) {
    double q[3];
    poly->GetPoint(ids->GetId(k), q);
    if (q[0] == 1 && q[1] == 0.5) junction = ids->GetId(k);
  }
  REQUIRE(junction >= 0);
  // Every polygon edge is shared by two polygons or lies on the outline (length 6): no crack, no hole.
  std::map<std::pair<vtkIdType, vtkIdType>, int> edges;
  for (vtkIdType i = 0; i < poly->GetNumberOfCells(); ++i) {
    vtkNew<vtkIdList> c;
    poly->GetCellPoints(i, c);
    for (vtkIdType k = 0; k < c->GetNumberOfIds(); ++k) {
      const vtkIdType a = c->GetId(k), e = c->GetId((k + 1) % c->GetNumberOfIds());
      ++edges[{std::min(a, e), std::max(a, e)}];
    }
  }
  double outline = 0;
  for (const auto& [e, count] : edges) {
    CHECK(count <= 2);
    if (count == 1) {
      double a[3], c[3];
      poly->GetPoint(e.first, a);
      poly->GetPoint(e.second, c);
      outline += std::hypot(a[0] - c[0], a[1] - c[1], a[2] - c[2]);
    }
  }
  CHECK(outline == Approx(6.0));
  // The junction's value averages the patches around it, the long-edged one included, and stays within their
  // range (the children touching it are the first (x = 2) and the fourth (x = 8) of the split patch).
  const double v = poly->GetPointData()->GetArray("x")->GetComponent(junction, 0);
  CHECK(v == Approx((1.0 * 1 + 0.25 * 2 + 0.25 * 8) / 1.5));
  for (vtkIdType i = 0; i < poly->GetNumberOfCells(); ++i)
    for (const double w : cell_point_values(poly, i)) {
      CHECK(w >= 1.0);
      CHECK(w <= 8.0);
    }
}
