// bench_polygons: CPU time of triangulating one n-gon against n (convex, star, comb; n = 256 .. 4096) with the
// fitted exponent of t ~ n^k, and of the coplanar-overlap search (mesh/coplanar_overlaps.h) and the whole
// validation on generated grids of F quads up to 10^6 faces; side by side, the former full-scan ear clipping
// (convex, n = 128 .. 512).
//
// Times are CPU seconds of the process (clock_gettime CLOCK_PROCESS_CPUTIME_ID: meaningful on a shared machine),
// each the best of 3 runs. The exponent is the least-squares slope of log t against log n.
// Usage: bench_polygons [--max-faces F]   (default 1e6)
#include <time.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "mesh/coplanar_overlaps.h"
#include "mesh/triangulate.h"
#include "mesh/validate.h"
#include "support/full_scan_ear_clipping.h"

using namespace radwalk;
using radwalk::test::full_scan_ear_clipping;

namespace {

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

template <class F>
double best_of_3(F&& f) {
  double best = 1e300;
  for (int k = 0; k < 3; ++k) {
    const double t0 = cpu_seconds();
    f();
    best = std::min(best, cpu_seconds() - t0);
  }
  return best;
}


std::vector<Vec3> polygon(const std::string& kind, std::size_t n) {
  std::vector<Vec3> p;
  if (kind == "comb") {
    const std::size_t teeth = n / 4;
    const double w = 1.0 / static_cast<double>(teeth);
    p = {{-0.5, -0.5, 0}, {0.5, -0.5, 0}};
    for (std::size_t k = teeth; k-- > 0;) {
      const double x = -0.5 + w * static_cast<double>(k);
      p.emplace_back(x + w, 0.5, 0);
      p.emplace_back(x + 0.5 * w, 0.5, 0);
      if (k > 0) {
        p.emplace_back(x + 0.5 * w, -0.4, 0);
        p.emplace_back(x, -0.4, 0);
      }
    }
    return p;
  }
  for (std::size_t k = 0; k < n; ++k) {
    const double a = 2 * M_PI * static_cast<double>(k) / static_cast<double>(n);
    const double r = kind == "star" && k % 2 ? 0.5 : 1.0;
    p.emplace_back(r * std::cos(a), r * std::sin(a), 0);
  }
  return p;
}

// A side x side grid of unit quads in z = 0 with a 1/4-unit bump every 7th row (so not every face is coplanar)
// and, on every 997th cell where the grid is flat, a quad laid half over it and half over its neighbour.
Mesh grid(std::size_t side) {
  Mesh mesh;
  mesh.path = "grid";
  Material light;
  light.name = "light";
  light.Ke = Rgb::Ones();
  mesh.materials = {light};
  auto z = [](std::size_t i) { return i % 7 == 0 ? 0.25 : 0.0; };
  for (std::size_t i = 0; i <= side; ++i)
    for (std::size_t j = 0; j <= side; ++j)
      mesh.vertices.emplace_back(static_cast<double>(i), static_cast<double>(j), z(j));
  auto v = [&](std::size_t i, std::size_t j) { return static_cast<std::int32_t>(i * (side + 1) + j); };
  for (std::size_t i = 0; i < side; ++i)
    for (std::size_t j = 0; j < side; ++j) {
      mesh.faces.push_back({v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)});
      if ((i * side + j) % 997 == 0 && z(j) == 0 && z(j + 1) == 0) {
        const auto base = static_cast<std::int32_t>(mesh.vertices.size());
        for (const auto& [x, y] : {std::pair{0.5, 0.0}, {1.5, 0.0}, {1.5, 1.0}, {0.5, 1.0}})
          mesh.vertices.emplace_back(static_cast<double>(i) + x, static_cast<double>(j) + y, 0.0);
        mesh.faces.push_back({base, base + 1, base + 2, base + 3});
      }
    }
  mesh.face_material.assign(mesh.faces.size(), 0);
  return mesh;
}

}  // namespace

int main(int argc, char** argv) {
  double max_faces = 1e6;
  for (int k = 1; k + 1 < argc; ++k)
    if (std::strcmp(argv[k], "--max-faces") == 0) max_faces = std::atof(argv[k + 1]);

  std::printf("triangulate_polygon: CPU ms (best of 3)\n%8s %10s %10s %10s\n", "n", "convex", "star", "comb");
  const std::vector<std::string> kinds = {"convex", "star", "comb"};
  std::vector<std::vector<double>> times(kinds.size());
  std::vector<double> ns;
  for (std::size_t n = 256; n <= kMaxPolygonCorners; n *= 2) {
    ns.push_back(static_cast<double>(n));
    std::printf("%8zu", n);
    for (std::size_t k = 0; k < kinds.size(); ++k) {
      const auto p = polygon(kinds[k], n);
      const double t = best_of_3([&] {
        if (!triangulate_polygon(p)) std::abort();
      });
      times[k].push_back(t);
      std::printf(" %10.3f", 1e3 * t);
    }
    std::printf("\n");
  }
  std::printf("%8s", "exponent");
  auto fit = [](const std::vector<double>& x, const std::vector<double>& y) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    const double m = static_cast<double>(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double lx = std::log(x[i]), ly = std::log(y[i]);
      sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
    }
    return (m * sxy - sx * sy) / (m * sxx - sx * sx);
  };
  for (std::size_t k = 0; k < kinds.size(); ++k) std::printf(" %10.2f", fit(ns, times[k]));
  // Side by side: the former full scan (every corner tested against every corner each round), convex only,
  // n = 128 .. 512 (it is cubic: 22 CPU s at n = 2048).
  std::printf("\n\nformer full-scan ear clipping, convex: CPU ms\n");
  std::vector<double> old_n, old_t;
  for (std::size_t n = 128; n <= 512; n *= 2) {
    const auto p = polygon("convex", n);
    const double t = best_of_3([&] {
      if (!full_scan_ear_clipping(p)) std::abort();
    });
    old_n.push_back(static_cast<double>(n));
    old_t.push_back(t);
    std::printf("%8zu %10.3f\n", n, 1e3 * t);
  }
  std::printf("%8s %10.2f", "exponent", fit(old_n, old_t));
  std::printf("\n\ncoplanar overlaps and validate_mesh on grids: CPU s\n%10s %10s %10s %12s\n", "faces", "overlaps",
              "found", "validate");
  for (const std::size_t side : {100, 316, 1000, 3162}) {
    if (side > 100 && static_cast<double>(side * side) > max_faces * 1.01) break;
    const Mesh mesh = grid(side);
    std::size_t found = 0;
    const double t0 = cpu_seconds();
    found = find_coplanar_overlaps(mesh).size();
    const double t_overlap = cpu_seconds() - t0;
    Mesh copy = mesh;
    const double t1 = cpu_seconds();
    validate_mesh(copy);
    const double t_validate = cpu_seconds() - t1;
    std::printf("%10zu %10.3f %10zu %12.3f\n", mesh.face_count(), t_overlap, found, t_validate);
  }
  return 0;
}
