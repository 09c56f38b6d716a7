#include "apps/finite_outputs.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace radwalk::app {
namespace {

// The advice of every refusal: the radiosity is linear in the emission.
std::string advice(double max_E) {
  return " (the largest emitted radiosity E = pi Ke is " + number_text(max_E) +
         "): divide Ke by a power of ten with --set MATERIAL.Ke=... and multiply the results by it";
}

[[noreturn]] void refuse(const std::string& what, const std::string& where, double max_E) {
  throw NumericalError(what + " of " + where + " overflows a double" + advice(max_E));
}

}  // namespace

void refuse_overflow(const Solution& s, const std::string& command, double max_E) {
  const std::pair<const PatchRgb*, const char*> named[] = {
      {&s.B, "the radiosity B"}, {&s.B_se, "the standard error B_se"}, {&s.var, "the per-sample variance var"}};
  for (const auto& [x, what] : named)
    for (Eigen::Index i = 0; i < x->rows(); ++i)
      for (Eigen::Index c = 0; c < x->cols(); ++c)
        if (std::isinf((*x)(i, c)))
          refuse(command + " (" + s.method + "): " + what,
                 "patch " + std::to_string(i) + ", channel " + "RGB"[c], max_E);
}

void refuse_overflow(const std::vector<CompareRow>& rows, double max_E) {
  for (const CompareRow& r : rows) {
    const std::pair<double, const char*> named[] = {
        {r.mean, "the mean"}, {r.var, "the per-walk variance var"}, {r.var_se, "the standard error var_se"}};
    for (const auto& [x, what] : named)
      if (std::isinf(x))
        refuse(std::string("compare (") + std::string(method_name(r.method)) + "): " + what,
               "patch " + std::to_string(r.patch) + ", channel " + "RGB"[r.channel], max_E);
  }
}

void refuse_overflow(const RgbImage& mean, const RgbImage& se, const std::string& file, double max_E) {
  const bool exr = file.size() >= 4 && file.compare(file.size() - 4, 4, ".exr") == 0;
  const double largest = exr ? double(std::numeric_limits<float>::max()) : std::numeric_limits<double>::max();
  for (const RgbImage* image : {&mean, &se})
    for (std::size_t k = 0; k < image->pixels.size(); ++k) {
      if (image->pixels[k].abs().maxCoeff() <= largest) continue;
      const std::string what =
          std::string("pathtrace: the image's ") + (image == &mean ? "mean radiance" : "standard error");
      const std::string where = "pixel (" + std::to_string(k % std::size_t(image->width)) + ", " +
                                std::to_string(k / std::size_t(image->width)) + ")";
      if (exr && std::isfinite(image->pixels[k].abs().maxCoeff()))
        throw NumericalError(what + " of " + where + " is " + number_text(image->pixels[k].abs().maxCoeff()) +
                             ", above the largest 32-bit float an EXR holds (3.4e38)" + advice(max_E));
      refuse(what, where, max_E);
    }
}

}  // namespace radwalk::app
