// A test tool, not a test: reads .npz form-factor files with read_npz (formfactor/npz.h) and prints what it read,
// so that tests/python/test_npz_mutations.py can compare radwalk's reading of a file with scipy's.
//
// Usage: radwalk_npz_read_tool N FILE...   (N: the expected patch count)
// One line per file, in order: "ok" and the CSR (indptr, indices, the bits of each float value in hexadecimal,
// each a comma-separated list, separated by spaces; "-" for an empty list), or "refused" and the InputError
// message. Exit 0 after the last file; any other exception prints "error" and its message and exits 4 at once.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#include "core/error.h"
#include "formfactor/npz.h"

namespace {

template <class T, class Format>
std::string list(const T* p, std::size_t n, Format&& format) {
  if (n == 0) return "-";
  std::string s;
  for (std::size_t k = 0; k < n; ++k) s += (k ? "," : "") + format(p[k]);
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s N FILE...\n", argv[0]);
    return 2;
  }
  const std::size_t n = std::strtoull(argv[1], nullptr, 10);
  for (int a = 2; a < argc; ++a) {
    try {
      const radwalk::SparseF F = radwalk::read_npz(argv[a], n);
      const auto nnz = static_cast<std::size_t>(F.nonZeros());
      const auto integer = [](std::int32_t v) { return std::to_string(v); };
      const auto bits = [](float v) {
        std::uint32_t b;
        std::memcpy(&b, &v, 4);
        char text[16];
        std::snprintf(text, sizeof text, "%08x", static_cast<unsigned>(b));
        return std::string(text);
      };
      std::printf("ok %s %s %s\n", list(F.outerIndexPtr(), std::size_t(F.rows()) + 1, integer).c_str(),
                  list(F.innerIndexPtr(), nnz, integer).c_str(), list(F.valuePtr(), nnz, bits).c_str());
    } catch (const radwalk::InputError& e) {
      std::printf("refused %s\n", e.what());
    } catch (const std::exception& e) {
      std::printf("error %s\n", e.what());
      return 4;
    }
  }
  return 0;
}
