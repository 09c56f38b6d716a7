#include "mesh/polygon_crossings.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "core/format_number.h"
#include "mesh/triangulate.h"

namespace radwalk {

namespace {

using Vec2 = Eigen::Vector2d;

double orient(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// Where the outline passes a meeting point: edge `edge` at parameter t (t = 0: at its start corner).
struct Pass {
  std::int32_t edge;
  double t;
  std::int32_t node;   // the meeting point
  std::int32_t point;  // its point index (a corner, or n + j for a crossing)
};

// Twice the signed area of the loop in the plane, and the sum of its terms' magnitudes (for its rounding).
std::pair<double, double> shoelace(const std::vector<Vec2>& q, const std::vector<std::int32_t>& loop) {
  double s = 0, magnitude = 0;
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const Vec2& a = q[static_cast<std::size_t>(loop[k])];
    const Vec2& b = q[static_cast<std::size_t>(loop[(k + 1) % loop.size()])];
    const double term = a.x() * b.y() - a.y() * b.x();
    s += term;
    magnitude += std::abs(a.x() * b.y()) + std::abs(a.y() * b.x());
  }
  return {s, magnitude};
}

}  // namespace

PolygonPieces split_at_crossings(const std::vector<Vec3>& corners, bool touches) {
  PolygonPieces out;
  const std::size_t n = corners.size();
  if (n < 4) return out;  // a triangle cannot cross itself

  // The plane: centroid, covariance's smallest eigenvector, turned along Newell's N.
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : corners) c += p;
  c /= static_cast<double>(n);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  Vec3 N = Vec3::Zero(), lo = corners[0], hi = corners[0];
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3 d = corners[k] - c;
    cov += d * d.transpose();
    N += d.cross(corners[(k + 1) % n] - c);
    lo = lo.cwiseMin(corners[k]);
    hi = hi.cwiseMax(corners[k]);
  }
  if (!cov.allFinite()) return out;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(cov);
  Vec3 normal = eigen.eigenvectors().col(0);
  if (normal.dot(N) < 0) normal = -normal;
  const Vec3 e1 = normal.unitOrthogonal(), e2 = normal.cross(e1);
  std::vector<Vec2> q(n);
  for (std::size_t k = 0; k < n; ++k) q[k] = Vec2((corners[k] - c).dot(e1), (corners[k] - c).dot(e2));

  // Candidate edge pairs: edges bucketed by the cells of a G x G grid their bounding boxes cover.
  Vec2 qlo = q[0], qhi = q[0];
  for (const Vec2& p : q) {
    qlo = qlo.cwiseMin(p);
    qhi = qhi.cwiseMax(p);
  }
  const auto G = static_cast<std::int64_t>(std::max(1.0, std::ceil(std::sqrt(static_cast<double>(n)))));
  auto cell = [&](double x, double low, double high) {
    if (!(high > low)) return std::int64_t{0};
    return std::clamp(static_cast<std::int64_t>((x - low) / (high - low) * static_cast<double>(G)), std::int64_t{0},
                      G - 1);
  };
  std::vector<std::array<std::int64_t, 4>> box(n);  // x0, x1, y0, y1 cell ranges of each edge
  std::vector<std::vector<std::int32_t>> cells(static_cast<std::size_t>(G * G));
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 &a = q[i], &b = q[(i + 1) % n];
    box[i] = {cell(std::min(a.x(), b.x()), qlo.x(), qhi.x()), cell(std::max(a.x(), b.x()), qlo.x(), qhi.x()),
              cell(std::min(a.y(), b.y()), qlo.y(), qhi.y()), cell(std::max(a.y(), b.y()), qlo.y(), qhi.y())};
    for (std::int64_t x = box[i][0]; x <= box[i][1]; ++x)
      for (std::int64_t y = box[i][2]; y <= box[i][3]; ++y)
        cells[static_cast<std::size_t>(x * G + y)].push_back(static_cast<std::int32_t>(i));
  }

  std::vector<Pass> passes;
  std::vector<Vec2> q_new;
  std::int32_t nodes = 0;
  std::vector<std::int32_t> corner_node(n, -1);
  auto node_of_corner = [&](std::size_t k) {
    if (corner_node[k] < 0) {
      corner_node[k] = nodes++;
      passes.push_back({static_cast<std::int32_t>(k), 0.0, corner_node[k], static_cast<std::int32_t>(k)});
    }
    return corner_node[k];
  };
  auto degenerate = [&](const std::string& why) {
    out = PolygonPieces();
    out.status = PolygonPieces::Status::degenerate;
    out.why = why;
    return out;
  };
  // Parameter of p along a -> b (p on its line).
  auto along = [](const Vec2& a, const Vec2& b, const Vec2& p) { return (p - a).dot(b - a) / (b - a).squaredNorm(); };
  bool overlap = false;
  std::size_t proper = 0;  // proper crossings
  for (std::int64_t x = 0; x < G; ++x)
    for (std::int64_t y = 0; y < G; ++y) {
      const auto& in = cells[static_cast<std::size_t>(x * G + y)];
      for (std::size_t u = 0; u < in.size(); ++u)
        for (std::size_t v = u + 1; v < in.size(); ++v) {
          auto i = static_cast<std::size_t>(std::min(in[u], in[v])), j = static_cast<std::size_t>(std::max(in[u], in[v]));
          // Each pair once: in the first cell both boxes cover.
          if (std::max(box[i][0], box[j][0]) != x || std::max(box[i][2], box[j][2]) != y) continue;
          if (j == i + 1 || (i == 0 && j == n - 1)) continue;  // neighbours meet at their shared corner
          const Vec2 &a = q[i], &b = q[(i + 1) % n], &p = q[j], &r = q[(j + 1) % n];
          const double o1 = orient(a, b, p), o2 = orient(a, b, r), o3 = orient(p, r, a), o4 = orient(p, r, b);
          if (((o1 < 0 && o2 > 0) || (o1 > 0 && o2 < 0)) && ((o3 < 0 && o4 > 0) || (o3 > 0 && o4 < 0))) {
            const double t = o3 / (o3 - o4), s = o1 / (o1 - o2);
            const Vec3 on_i = corners[i] + t * (corners[(i + 1) % n] - corners[i]);
            const Vec3 on_j = corners[j] + s * (corners[(j + 1) % n] - corners[j]);
            const auto point = static_cast<std::int32_t>(n + out.new_points.size());
            out.new_points.push_back(0.5 * (on_i + on_j));
            q_new.push_back(a + t * (b - a));
            passes.push_back({static_cast<std::int32_t>(i), t, nodes, point});
            passes.push_back({static_cast<std::int32_t>(j), s, nodes, point});
            ++nodes;
            ++proper;
            continue;
          }
          if (o1 == 0 && o2 == 0) {  // on one line: do they share a stretch?
            const double s0 = along(a, b, p), s1 = along(a, b, r);
            if (std::max(s0, s1) > 0 && std::min(s0, s1) < 1) overlap = true;
            continue;
          }
          // The start corner of one edge strictly inside the other.
          auto touch = [&](std::size_t corner, std::size_t edge, double o, const Vec2& from, const Vec2& to) {
            if (o != 0) return;
            const double s = along(from, to, q[corner]);
            if (!(s > 0 && s < 1)) return;
            const std::int32_t node = node_of_corner(corner);
            passes.push_back({static_cast<std::int32_t>(edge), s, node, static_cast<std::int32_t>(corner)});
          };
          touch(j, i, o1, a, b);
          touch(i, j, o3, p, r);
        }
    }
  {
    // Two corners at the same point (not neighbours: the caller merged those).
    std::map<std::array<double, 3>, std::size_t> seen;
    for (std::size_t k = 0; k < n; ++k) {
      const auto [it, added] = seen.emplace(std::array<double, 3>{corners[k].x(), corners[k].y(), corners[k].z()}, k);
      if (added) continue;
      const std::int32_t node = node_of_corner(it->second);
      if (corner_node[k] >= 0) return degenerate("more than two passes of the outline through one point");
      corner_node[k] = node;
      passes.push_back({static_cast<std::int32_t>(k), 0.0, node, static_cast<std::int32_t>(it->second)});
    }
  }
  if (proper == 0 && (!touches || (nodes == 0 && !overlap))) return out;  // simple
  if (overlap) return degenerate("two of its edges overlap along a stretch");

  // Planar enough for a crossing in the plane to be one in space.
  double off = 0;
  for (const Vec3& p : corners) off = std::max(off, std::abs((p - c).dot(normal)));
  const double diagonal = (hi - lo).norm();
  if (!(off <= kCrossingPlanarity * diagonal)) {
    out = PolygonPieces();
    out.status = PolygonPieces::Status::nonplanar;
    out.why = "its outline crosses itself in projection, but a corner is " +
              std::to_string(100 * off / diagonal) + "% of its size off its plane";
    return out;
  }

  // The stations of the outline in order: each edge's start corner, then its meeting points by parameter.
  std::sort(passes.begin(), passes.end(), [](const Pass& x, const Pass& y) {
    return x.edge != y.edge ? x.edge < y.edge : x.t < y.t;
  });
  std::vector<std::int32_t> station_point, station_node;
  {
    std::size_t k = 0;
    for (std::size_t e = 0; e < n; ++e) {
      bool start_is_node = false;
      for (std::size_t m = k; m < passes.size() && passes[m].edge == static_cast<std::int32_t>(e); ++m)
        start_is_node = start_is_node || passes[m].t == 0.0;
      if (!start_is_node) {
        station_point.push_back(static_cast<std::int32_t>(e));
        station_node.push_back(-1);
      }
      for (; k < passes.size() && passes[k].edge == static_cast<std::int32_t>(e); ++k) {
        station_point.push_back(passes[k].point);
        station_node.push_back(passes[k].node);
      }
    }
  }
  const std::size_t S = station_point.size();
  std::vector<std::int32_t> partner(S, -1);
  {
    std::vector<std::vector<std::int32_t>> at(static_cast<std::size_t>(nodes));
    for (std::size_t s = 0; s < S; ++s)
      if (station_node[s] >= 0) at[static_cast<std::size_t>(station_node[s])].push_back(static_cast<std::int32_t>(s));
    for (const auto& a : at) {
      if (a.size() != 2) return degenerate("more than two passes of the outline through one point");
      partner[static_cast<std::size_t>(a[0])] = a[1];
      partner[static_cast<std::size_t>(a[1])] = a[0];
    }
  }

  // The loops: arriving at a meeting point along one pass, leave along the other.
  std::vector<Vec2> q_all = q;
  q_all.insert(q_all.end(), q_new.begin(), q_new.end());
  std::vector<char> visited(S, 0);
  std::vector<std::pair<double, double>> signed_area;
  std::size_t first_loop = 0;
  for (std::size_t s0 = 0; s0 < S; ++s0) {
    if (visited[s0]) continue;
    std::vector<std::int32_t> loop;
    bool holds_start = false;
    std::size_t s = s0;
    do {
      visited[s] = 1;
      holds_start = holds_start || s == 0;
      loop.push_back(station_point[s]);
      s = (static_cast<std::size_t>(partner[s] >= 0 ? partner[s] : static_cast<std::int32_t>(s)) + 1) % S;
    } while (s != s0);
    if (loop.size() < 3) continue;  // no area
    if (holds_start) first_loop = out.pieces.size();
    out.pieces.push_back(std::move(loop));
    signed_area.push_back(shoelace(q_all, out.pieces.back()));
  }
  // Nesting: a piece inside another (the pieces never cross, so one interior point decides) winding the same way
  // covers a region the outline winds around twice (a pentagram's centre): left out, the region counted once. One
  // winding the other way inside another would make a hole (winding 0): not split.
  {
    auto winding = [&](const Vec2& x, const std::vector<std::int32_t>& loop) {
      int w = 0;
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const Vec2& a = q_all[static_cast<std::size_t>(loop[k])];
        const Vec2& b = q_all[static_cast<std::size_t>(loop[(k + 1) % loop.size()])];
        if (a.y() <= x.y()) {
          if (b.y() > x.y() && orient(a, b, x) > 0) ++w;
        } else if (b.y() <= x.y() && orient(a, b, x) < 0) {
          --w;
        }
      }
      return w;
    };
    std::vector<char> keep(out.pieces.size(), 1);
    for (std::size_t i = 0; i < out.pieces.size() && out.pieces.size() > 1; ++i) {
      std::vector<Vec3> p3;
      for (const std::int32_t k : out.pieces[i])
        p3.push_back(static_cast<std::size_t>(k) < n ? corners[static_cast<std::size_t>(k)]
                                                     : out.new_points[static_cast<std::size_t>(k) - n]);
      const auto t = triangulate_polygon(p3);
      if (!t || t->empty()) continue;  // left to triangulate_pieces
      const auto& tri = t->front();
      const Vec3 g = (p3[static_cast<std::size_t>(tri[0])] + p3[static_cast<std::size_t>(tri[1])] +
                      p3[static_cast<std::size_t>(tri[2])]) / 3;
      const Vec2 x((g - c).dot(e1), (g - c).dot(e2));
      for (std::size_t j = 0; j < out.pieces.size(); ++j) {
        if (j == i || std::abs(signed_area[j].first) <= std::abs(signed_area[i].first)) continue;
        if (winding(x, out.pieces[j]) == 0) continue;
        if (signed_area[i].first * signed_area[j].first < 0)
          return degenerate("a loop of its outline lies inside another and winds the other way (a hole)");
        keep[i] = 0;
        break;
      }
    }
    std::size_t m = 0;
    for (std::size_t k = 0; k < out.pieces.size(); ++k) {
      if (!keep[k]) {
        ++out.nested;
        continue;
      }
      if (m != k) {  // (a vector moved onto itself is left empty)
        out.pieces[m] = std::move(out.pieces[k]);
        signed_area[m] = signed_area[k];
      }
      if (k == first_loop) first_loop = m;
      ++m;
    }
    out.pieces.resize(m);
    signed_area.resize(m);
    if (first_loop >= m) first_loop = 0;
  }
  double total = 0;
  for (const auto& a : signed_area) total += a.first;
  const double sign = total > 0 ? 1 : total < 0 ? -1 : (signed_area.empty() || signed_area[first_loop].first >= 0 ? 1 : -1);
  for (std::size_t k = 0; k < out.pieces.size(); ++k) {
    out.area += 0.5 * std::abs(signed_area[k].first);
    if (signed_area[k].first * sign < 0) {
      std::reverse(out.pieces[k].begin(), out.pieces[k].end());
      ++out.reversed;
    }
  }
  out.status = PolygonPieces::Status::split;
  out.meetings = static_cast<std::size_t>(nodes);
  return out;
}

std::string split_message(const std::string& what, const PolygonPieces& pieces, std::size_t triangles) {
  const std::size_t m = pieces.meetings, k = pieces.pieces.size();
  std::string s = what + " crosses itself: split at " + std::to_string(m) +
                  (m == 1 ? " crossing" : " crossings") + " into " + std::to_string(k) + " simple " +
                  (k == 1 ? "piece" : "pieces") + " of area " + format_number(pieces.area) +
                  " in all (the lobes' areas as drawn)";
  if (pieces.nested > 0)
    s += ", " + std::to_string(pieces.nested) + (pieces.nested == 1 ? " piece" : " pieces") +
         " inside another left out (a region the outline winds around twice is covered once)";
  if (pieces.reversed > 0)
    s += ", " + std::to_string(pieces.reversed) + (pieces.reversed == 1 ? " lobe" : " lobes") +
         " turned to face along the polygon's dominant normal";
  return s + ", " + std::to_string(triangles) + " triangles";
}

std::string new_vertices(std::size_t first, std::size_t end) {
  if (end <= first) return "";
  if (end == first + 1) return "; the crossing is new vertex " + std::to_string(first + 1);
  return "; the crossings are new vertices " + std::to_string(first + 1) + " to " + std::to_string(end);
}

std::optional<std::vector<std::array<std::int32_t, 3>>> triangulate_pieces(const std::vector<Vec3>& corners,
                                                                           const PolygonPieces& pieces) {
  auto point = [&](std::int32_t k) -> const Vec3& {
    const auto u = static_cast<std::size_t>(k);
    return u < corners.size() ? corners[u] : pieces.new_points[u - corners.size()];
  };
  std::vector<std::array<std::int32_t, 3>> triangles;
  for (const auto& loop : pieces.pieces) {
    std::vector<Vec3> p;
    for (const std::int32_t k : loop) p.push_back(point(k));
    const auto t = triangulate_polygon(p);
    if (!t) {
      // A piece without area (its vector area within rounding of 0: about n ulps of its terms) carries nothing.
      Vec3 N = Vec3::Zero();
      double magnitude = 0;
      for (std::size_t k = 0; k < p.size(); ++k) {
        const Vec3 term = (p[k] - p[0]).cross(p[(k + 1) % p.size()] - p[0]);
        N += term;
        magnitude += term.norm();
      }
      if (N.norm() <= static_cast<double>(p.size()) * std::numeric_limits<double>::epsilon() * magnitude) continue;
      return std::nullopt;
    }
    for (const auto& tri : *t)
      triangles.push_back({loop[static_cast<std::size_t>(tri[0])], loop[static_cast<std::size_t>(tri[1])],
                           loop[static_cast<std::size_t>(tri[2])]});
  }
  if (triangles.empty()) return std::nullopt;
  return triangles;
}

}  // namespace radwalk
