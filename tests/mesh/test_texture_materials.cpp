// Materials as modelling tools write them: Kd times a map_Kd texture becomes Kd times the texture's mean linear
// colour (PNG and JPEG, sRGB decoded), a texture that cannot be read gives Kd times 0.5 with a warning, and every
// refusal of a material names the options that fix it (--set, --rho-scale).
#include <catch2/catch.hpp>

#include <map>
#include <string>
#include <vector>

#include <png.h>

#include "core/error.h"
#include "core/srgb.h"
#include "mesh/read_obj.h"
#include "mesh/texture_mean.h"
#include "mesh/validate.h"

using namespace radwalk;

namespace {

// A PNG of the given 8-bit sRGB RGB pixels, written with libpng (independent of the reader's code path).
std::string png_of(int width, int height, const std::vector<unsigned char>& rgb) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(width);
  image.height = static_cast<png_uint_32>(height);
  image.format = PNG_FORMAT_RGB;
  png_alloc_size_t size = 0;
  REQUIRE(png_image_write_to_memory(&image, nullptr, &size, 0, rgb.data(), 0, nullptr));
  std::string bytes(size, '\0');
  REQUIRE(png_image_write_to_memory(&image, bytes.data(), &size, 0, rgb.data(), 0, nullptr));
  bytes.resize(size);
  return bytes;
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

const Finding* first_of(const std::vector<Finding>& findings, const std::string& kind) {
  for (const Finding& f : findings)
    if (f.kind == kind) return &f;
  return nullptr;
}

Mesh read_with(const std::string& mtl, const std::map<std::string, std::string>& files) {
  std::map<std::string, std::string> all = files;
  all["dir/scene.mtl"] = mtl;
  const MtlSource source{[all](const std::string& p) { return all.count(p) > 0; },
                         [all](const std::string& p) { return all.at(p); }};
  return read_obj_text("dir/scene.obj",
                       "mtllib scene.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl m\nf 1 2 3\n", source);
}

}  // namespace

TEST_CASE("the mean colour of a texture is taken in linear reflectance", "[mesh][texture]") {
  // Half red, half black: the mean of the linear values is (0.5, 0, 0), not the sRGB mean's 0.214.
  const TextureMean a = texture_mean(png_of(2, 1, {255, 0, 0, 0, 0, 0}));
  REQUIRE(a.mean);
  CHECK((*a.mean)[0] == Approx(0.5).epsilon(1e-15));
  CHECK((*a.mean)[1] == 0);
  CHECK(a.width == 2);
  // Mid grey 128: linear_from_srgb(128 / 255) = 0.2158605 (IEC 61966-2-1).
  const TextureMean g = texture_mean(png_of(1, 1, {128, 128, 128}));
  REQUIRE(g.mean);
  CHECK((*g.mean)[2] == Approx(0.21586050011389926).epsilon(1e-12));
  const TextureMean bad = texture_mean("GIF89a....");
  CHECK_FALSE(bad.mean);
  CHECK(contains(bad.why, "not a PNG or JPEG"));
  const TextureMean broken = texture_mean(png_of(2, 1, {255, 0, 0, 0, 0, 0}).substr(0, 40));
  CHECK_FALSE(broken.mean);
  CHECK(contains(broken.why, "PNG"));
}

TEST_CASE("Kd with map_Kd uses the texture's mean colour, with a warning", "[mesh][texture]") {
  const std::string tex = png_of(2, 1, {255, 0, 0, 0, 0, 0});
  Mesh mesh = read_with("newmtl m\nKd 0.8 0.8 0.8\nmap_Kd -s 1 1 1 -bm 0.5 tex dir/wood.png\n",
                        {{"dir/tex dir/wood.png", tex}});
  CHECK(mesh.materials[0].Kd[0] == Approx(0.4).epsilon(1e-15));
  CHECK(mesh.materials[0].Kd[1] == 0);
  const Finding* f = first_of(mesh.findings, "texture mean colour used");
  REQUIRE(f != nullptr);
  CHECK(f->file == "dir/scene.mtl");
  CHECK(f->line == 3);
  CHECK(contains(f->message, "material 'm'"));
  CHECK(contains(f->message, "2 x 1 pixels"));
  // Kd 1 1 1 (white, the texture's multiplier) is no longer refused.
  Mesh white = read_with("newmtl m\nKd 1 1 1\nmap_Kd wood.png\n", {{"dir/wood.png", tex}});
  validate_mesh(white);
  CHECK(white.materials[0].Kd[0] == Approx(0.5).epsilon(1e-15));
  // No Kd at all: the texture alone.
  Mesh bare = read_with("newmtl m\nmap_Kd wood.png\n", {{"dir/wood.png", tex}});
  CHECK(bare.materials[0].Kd[0] == Approx(0.5).epsilon(1e-15));
}

TEST_CASE("a texture that cannot be read gives Kd times 0.5 with a warning naming --set", "[mesh][texture]") {
  Mesh missing = read_with("newmtl m\nKd 1 1 1\nmap_Kd missing.jpg\n", {});
  CHECK((missing.materials[0].Kd == Rgb::Constant(0.5)).all());
  const Finding* f = first_of(missing.findings, "texture not read");
  REQUIRE(f != nullptr);
  CHECK(contains(f->message, "not found"));
  CHECK(contains(f->message, "--set 'm.Kd=r,g,b'"));
  Mesh unreadable = read_with("newmtl m\nKd 0.6 0.6 0.6\nmap_Kd wood.bmp\n", {{"dir/wood.bmp", "BM...."}});
  CHECK(unreadable.materials[0].Kd[0] == Approx(0.3).epsilon(1e-15));
  CHECK(contains(first_of(unreadable.findings, "texture not read")->message, "not a PNG or JPEG"));
}

TEST_CASE("every refusal of a material names the options that fix it", "[mesh][texture]") {
  Mesh bright = read_with("newmtl m\nKd 1 0.5 0.5\n", {});
  std::string message;
  try {
    validate_mesh(bright);
  } catch (const InputError& e) {
    message = e.what();
  }
  CHECK(contains(message, "reflectance out of range"));
  CHECK(contains(message, "--set 'm.Kd=r,g,b'"));
  CHECK(contains(message, "--rho-scale"));
  Mesh negative = read_with("newmtl m\nKd 0.5\nKe -1 0 0\n", {});
  message.clear();
  try {
    validate_mesh(negative);
  } catch (const InputError& e) {
    message = e.what();
  }
  CHECK(contains(message, "--set 'm.Ke=r,g,b'"));
}
