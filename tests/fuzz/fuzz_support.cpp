#include "fuzz_support.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "mesh/face_geometry.h"
#include "mesh/validate.h"

namespace radwalk::fuzz {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// Valid UTF-8 by the Unicode table of well-formed byte sequences (no overlongs, no surrogates, at most
// U+10FFFF). Written out here rather than taken from core/error.h, so that the oracle does not share the code
// it checks.
bool valid_utf8(std::string_view s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const auto b = static_cast<unsigned char>(s[i]);
    if (b < 0x80) {
      ++i;
      continue;
    }
    std::size_t n = 0;
    unsigned char lo = 0x80, hi = 0xbf;  // range of the second byte
    if (b >= 0xc2 && b <= 0xdf)
      n = 2;
    else if (b == 0xe0)
      n = 3, lo = 0xa0;
    else if ((b >= 0xe1 && b <= 0xec) || b == 0xee || b == 0xef)
      n = 3;
    else if (b == 0xed)
      n = 3, hi = 0x9f;
    else if (b == 0xf0)
      n = 4, lo = 0x90;
    else if (b >= 0xf1 && b <= 0xf3)
      n = 4;
    else if (b == 0xf4)
      n = 4, hi = 0x8f;
    else
      return false;
    if (i + n > s.size()) return false;
    const auto second = static_cast<unsigned char>(s[i + 1]);
    if (second < lo || second > hi) return false;
    for (std::size_t k = 2; k < n; ++k)
      if ((static_cast<unsigned char>(s[i + k]) & 0xc0) != 0x80) return false;
    i += n;
  }
  return true;
}

std::string quoted(std::string_view s) {
  std::string q(1, '\'');
  return q.append(printable(s)).append(1, '\'');
}

std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

}  // namespace

void fail(const std::string& what) {
  std::fprintf(stderr, "\nfuzz oracle failed: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

std::pair<std::string_view, std::string_view> split_at(std::string_view input, std::string_view separator) {
  const std::size_t at = input.find(separator);
  if (at == std::string_view::npos) return {input, {}};
  return {input.substr(0, at), input.substr(at + separator.size())};
}

MtlSource fuzz_libraries(std::string_view mtl, std::vector<std::string>& files) {
  MtlSource libraries;
  libraries.exists = [](const std::string& path) { return path.find_first_of(" \t") == std::string::npos; };
  libraries.read = [mtl, &files](const std::string& path) {
    files.push_back(path);
    return std::string(mtl);
  };
  return libraries;
}

void check_refusal_message(const std::string& message, const std::vector<std::string>& files) {
  RADWALK_FUZZ_CHECK(message.find('\n') == std::string::npos,
                     "message on more than one line: " + quoted(message));
  for (const char c : message)
    RADWALK_FUZZ_CHECK(static_cast<unsigned char>(c) >= 0x20 && c != 0x7f,
                       "raw control character in the message " + quoted(message));
  RADWALK_FUZZ_CHECK(valid_utf8(message), "message is not valid UTF-8: " + quoted(message));
  bool names_a_file = false;
  for (const std::string& file : files) {
    const std::string prefix = printable(file) + ":";
    names_a_file = names_a_file || message.compare(0, prefix.size(), prefix) == 0;
  }
  std::string expected;
  for (const std::string& file : files) expected += (expected.empty() ? "" : ", ") + quoted(file);
  RADWALK_FUZZ_CHECK(names_a_file,
                     "message " + quoted(message) + " does not start with one of the files " + expected);
}

void check_read_mesh(const Mesh& mesh) {
  const std::size_t n = mesh.face_count();
  RADWALK_FUZZ_CHECK(mesh.face_material.size() == n && mesh.face_line.size() == n,
                     "per-face arrays of another size");
  // A non-finite coordinate is read as it is (validate_mesh refuses it with the scene's other findings).
  for (std::size_t f = 0; f < n; ++f) {
    const auto& c = mesh.faces[f];
    RADWALK_FUZZ_CHECK(c[0] >= 0 && c[1] >= 0 && c[2] >= 0 && c[3] >= -1,
                       "face " + std::to_string(f) + ": corners");
    RADWALK_FUZZ_CHECK(mesh.face_material[f] >= -1 &&
                           mesh.face_material[f] < static_cast<std::int32_t>(mesh.materials.size()),
                       "face " + std::to_string(f) + ": material index");
  }
}

void check_warnings(const Mesh& mesh, const std::vector<std::string>& files) {
  for (const std::string& w : mesh.warnings) check_refusal_message(w, files);
}

void check_validated_mesh(const Mesh& mesh) {
  for (const Vec3& p : mesh.vertices) RADWALK_FUZZ_CHECK(p.allFinite(), "a non-finite vertex was accepted");
  const std::size_t n = mesh.face_count();
  RADWALK_FUZZ_CHECK(n > 0, "validation accepted a mesh without faces");
  RADWALK_FUZZ_CHECK(mesh.face_material.size() == n && mesh.face_line.size() == n,
                     "per-face arrays of another size");
  for (std::size_t f = 0; f < n; ++f) {
    const std::string face = "face " + std::to_string(f);
    const auto& c = mesh.faces[f];
    for (int k = 0; k < mesh.corner_count(f); ++k) {
      const std::int32_t v = c[static_cast<std::size_t>(k)];
      RADWALK_FUZZ_CHECK(v >= 0 && static_cast<std::size_t>(v) < mesh.vertices.size(),
                         face + ": corner out of range");
      RADWALK_FUZZ_CHECK(mesh.vertices[static_cast<std::size_t>(v)].allFinite(),
                         face + ": non-finite corner");
    }
    const double area = face_area(mesh, f);
    RADWALK_FUZZ_CHECK(std::isfinite(area) && area > 0, face + ": area " + num(area));
    const std::int32_t m = mesh.face_material[f];
    RADWALK_FUZZ_CHECK(m >= 0 && static_cast<std::size_t>(m) < mesh.materials.size(),
                       face + ": no valid material");
    const Material& mat = mesh.materials[static_cast<std::size_t>(m)];
    const std::string material = face + ": material " + quoted(mat.name);
    RADWALK_FUZZ_CHECK(mat.Kd.allFinite() && (mat.Kd >= 0).all() && (mat.Kd < 1).all(),
                       material + ": rho not in [0, 1)");
    const Rgb E = kPi * mat.Ke;
    RADWALK_FUZZ_CHECK(mat.Ke.allFinite() && E.allFinite() && (mat.Ke >= 0).all(),
                       material + ": emission not finite and >= 0");
  }
}

void check_patches(const Mesh& mesh, const PatchSet& patches, double max_edge) {
  const std::size_t n = patches.size();
  RADWALK_FUZZ_CHECK(patches.corners.size() == n && patches.face.size() == n &&
                         patches.material.size() == n && patches.rho.size() == n && patches.E.size() == n &&
                         patches.normal.size() == n && patches.centroid.size() == n,
                     "per-patch arrays of different sizes");
  if (!(max_edge > 0))
    RADWALK_FUZZ_CHECK(n == mesh.face_count(), "without subdivision patch f must be face f");
  // Patches come in face order and name their input face (Mesh::source_face): the pieces of a repaired polygon
  // share it, so the patches are checked per input face, against all of that face's pieces together.
  std::size_t i = 0;
  for (std::size_t f = 0; f < mesh.face_count();) {
    const long source = mesh.source_face(f);
    std::size_t end = f;
    while (end < mesh.face_count() && mesh.source_face(end) == source) ++end;  // mesh faces [f, end)
    const std::string face = "input face " + std::to_string(source);
    const Material& mat = mesh.materials[static_cast<std::size_t>(mesh.face_material[f])];
    // The pieces' scale, for the rounding allowance: the longest side or diagonal and the largest |coordinate|.
    double longest = 0, reach = 0, area = 0, ambiguity = 0;
    for (std::size_t q = f; q < end; ++q) {
      const int corners = mesh.corner_count(q);
      auto corner = [&](int k) -> const Vec3& {
        return mesh.vertices[static_cast<std::size_t>(mesh.faces[q][static_cast<std::size_t>(k)])];
      };
      for (int u = 0; u < corners; ++u) {
        reach = std::max(reach, corner(u).cwiseAbs().maxCoeff());
        for (int v = u + 1; v < corners; ++v) longest = std::max(longest, (corner(u) - corner(v)).norm());
      }
      // A slightly bent quad has no one area: its triangulations and its bilinear surface (where its patches lie)
      // differ. Validation splits every quad whose area ambiguity (face_geometry.h) exceeds the tolerance, so what
      // is left is bounded by it; the allowance is twice the quad's own ambiguity (0 for a planar quad).
      const double a = face_area(mesh, q), spread = quad_area_ambiguity(mesh, q);
      area += a;
      RADWALK_FUZZ_CHECK(spread <= ValidationTolerances{}.area_ambiguity,
                         face + ": validation kept a quad of area ambiguity " + num(spread));
      ambiguity += 2 * spread * a;
    }
    double sum = 0;
    std::size_t count = 0;
    for (; i < n && patches.face[i] == static_cast<std::int32_t>(source); ++i, ++count) {
      const std::string patch = face + ", patch " + std::to_string(i);
      // The pieces of one input face may carry different materials: a piece that met a back-to-back duplicate
      // has the two-sided copy of the face's material (same Kd and Ke).
      bool of_a_piece = false;
      for (std::size_t q = f; q < end; ++q) of_a_piece = of_a_piece || patches.material[i] == mesh.face_material[q];
      RADWALK_FUZZ_CHECK(of_a_piece, patch + ": material of another face");
      const Material& own = mesh.materials[static_cast<std::size_t>(patches.material[i])];
      RADWALK_FUZZ_CHECK((patches.rho[i] == own.Kd).all() && (patches.E[i] == kPi * own.Ke).all() &&
                             (own.Kd == mat.Kd).all() && (own.Ke == mat.Ke).all(),
                         patch + ": rho or E not its material's");
      RADWALK_FUZZ_CHECK(patches.rho[i].allFinite() && patches.E[i].allFinite(),
                         patch + ": non-finite rho or E");
      const double a = patches.area[i];
      RADWALK_FUZZ_CHECK(std::isfinite(a) && a >= 0, patch + ": area " + num(a));
      RADWALK_FUZZ_CHECK(patches.normal[i].allFinite() && std::abs(patches.normal[i].norm() - 1) < 1e-9,
                         patch + ": normal not a unit vector");
      sum += a;
      const int k = patches.corner_count(i);
      for (int c = 0; c < k; ++c) {
        const int index = patches.corners[i][static_cast<std::size_t>(c)];
        RADWALK_FUZZ_CHECK(index >= 0 && static_cast<std::size_t>(index) < patches.points.size(),
                           patch + ": corner out of range");
        if (max_edge > 0) {
          const double edge = (patches.corner(i, (c + 1) % k) - patches.corner(i, c)).norm();
          RADWALK_FUZZ_CHECK(edge <= max_edge * (1 + 1e-9) + 16 * kEps * reach,
                             patch + ": edge " + num(edge) + " longer than max edge " + num(max_edge));
        } else {
          // Without subdivision patch i is mesh face i (a piece of this input face).
          const std::size_t q = f + count;
          RADWALK_FUZZ_CHECK(
              q < end && k == mesh.corner_count(q) &&
                  patches.corner(i, c) ==
                      mesh.vertices[static_cast<std::size_t>(mesh.faces[q][static_cast<std::size_t>(c)])],
              patch + ": corners are not the face's");
        }
      }
    }
    RADWALK_FUZZ_CHECK(count > 0, face + ": no patch (patches out of face order?)");
    const double allowance =
        64 * kEps * (area + reach * longest * static_cast<double>(2 + count)) + ambiguity;
    RADWALK_FUZZ_CHECK(std::abs(sum - area) <= allowance, face + ": its " + std::to_string(count) +
                                                              " patches add up to " + num(sum) +
                                                              ", the face's area is " + num(area));
    f = end;
  }
  RADWALK_FUZZ_CHECK(i == n, "patches after the last face, or out of face order");
}

}  // namespace radwalk::fuzz
