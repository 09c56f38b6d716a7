// The EXR, PNG and Matrix Market writers on a real full disk (issue 12, like the .vtp test in test_vtp.cpp): a
// 256 KiB tmpfs holding an old file; writing a new file that cannot fit fails with one line naming the file and
// leaves the old file as it was and nothing else (no temporary). Skipped with a message where mounting is not
// permitted (not root, or no mount permission in a container).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <unistd.h>

#include "core/error.h"
#include "core/image.h"
#include "formfactor/matrix_market.h"
#include "io/exr_writer.h"
#include "io/png_writer.h"

namespace fs = std::filesystem;
using namespace radwalk;

namespace {

std::string bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Mounts a 256 KiB tmpfs, writes the small file with write(path, false), then expects write(path, true) (a file
// too large for what is left) to throw an InputError naming the file, with the old bytes kept and no other file.
void check_full_disk(const std::string& name, const std::function<void(const std::string&, bool)>& write) {
  const auto mnt = fs::temp_directory_path() / ("radwalk_full_" + name + "_" + std::to_string(::getpid()));
  fs::create_directories(mnt);
  if (std::system(("mount -t tmpfs -o size=256k tmpfs " + mnt.string() + " 2>/dev/null").c_str()) != 0) {
    WARN("skipped: cannot mount a tmpfs here (needs root and mount permission)");
    fs::remove(mnt);
    return;
  }
  const fs::path path = mnt / name;
  write(path.string(), false);
  const std::string before = bytes_of(path);
  REQUIRE(!before.empty());
  try {
    write(path.string(), true);
    FAIL_CHECK("writing " << name << " on a full disk did not fail");
  } catch (const InputError& e) {
    const std::string what = e.what();
    CHECK(what.find(name) != std::string::npos);
    CHECK(what.find('\n') == std::string::npos);
  }
  CHECK(bytes_of(path) == before);
  CHECK(std::distance(fs::directory_iterator(mnt), fs::directory_iterator()) == 1);
  std::system(("umount " + mnt.string()).c_str());
  fs::remove(mnt);
}

// An image of incompressible noise: 1024 x 512 pixels (12 bytes each as float EXR, 3 as PNG: over 256 KiB).
RgbImage noise_image(bool large) {
  const int w = large ? 1024 : 4, h = large ? 512 : 4;
  RgbImage image(w, h);
  std::uint64_t x = 88172645463325252ULL;
  for (Rgb& p : image.pixels)
    for (int c = 0; c < 3; ++c) {
      x ^= x << 13;
      x ^= x >> 7;
      x ^= x << 17;
      p[c] = double(x >> 11) * 0x1p-53;
    }
  return image;
}

}  // namespace

TEST_CASE("write_exr on a full disk fails in one line and keeps the old file", "[io][exr][fault]") {
  check_full_disk("out.exr", [](const std::string& path, bool large) {
    write_exr(path, noise_image(large), ExrPixelType::float32, "0123456789abcdef");
  });
}

TEST_CASE("write_png on a full disk fails in one line and keeps the old file", "[io][png][fault]") {
  check_full_disk("out.png", [](const std::string& path, bool large) {
    write_png(path, noise_image(large), 1.0, "0123456789abcdef");
  });
}

TEST_CASE("write_matrix_market on a full disk fails in one line and keeps the old file", "[io][matrix_market][fault]") {
  check_full_disk("F.mtx", [](const std::string& path, bool large) {
    // 200 x 200 with every entry (about 40000 lines of 20 bytes: 800 KB), or 2 x 2.
    const int n = large ? 200 : 2;
    std::vector<Eigen::Triplet<float>> t;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) t.emplace_back(i, j, float(1.0 / (n + 1) * (0.5 + 0.5 * std::sin(i * 7.0 + j))));
    SparseF F(n, n);
    F.setFromTriplets(t.begin(), t.end());
    write_matrix_market(path, F, "0123456789abcdef");
  });
}
