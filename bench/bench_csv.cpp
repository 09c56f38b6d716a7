// bench_csv: the per-patch CSV writer (io/csv_writer.h: std::to_chars into a row buffer) against the former one
// (printf's %.12g per number, every cell inserted into the stream: tests/support/csv_reference.h), side by side
// in one run on the same patches and fields, the bytes compared.
//
// Scene: meshes/cornell_box.obj patched to about each N of --sizes; the fields of `radwalk pathtrace --csv`
// (B, B_se and B_var, three channels each) filled with random values. CPU seconds of the process, best of
// --repeat runs; the files go to the temporary directory and are removed.
// Usage: bench_csv [--sizes 1e5,1e6] [--repeat 3]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bench_scene.h"
#include "core/rng.h"
#include "io/csv_writer.h"
#include "support/csv_reference.h"

using namespace radwalk;
using radwalk::bench::cpu_seconds;

int main(int argc, char** argv) {
  std::vector<double> sizes = {1e5, 1e6};
  long repeat = 3;
  for (int a = 1; a + 1 < argc; a += 2) {
    const std::string k = argv[a], v = argv[a + 1];
    if (k == "--sizes") {
      sizes.clear();
      std::stringstream in(v);
      for (std::string item; std::getline(in, item, ',');) sizes.push_back(std::atof(item.c_str()));
    } else if (k == "--repeat") {
      repeat = std::atol(v.c_str());
    } else {
      std::fprintf(stderr, "bench_csv: unknown option %s\n", k.c_str());
      return 2;
    }
  }
  const auto dir = std::filesystem::temp_directory_path();
  std::printf("bench_csv: CPU seconds, best of %ld\n%10s %12s %12s %8s %10s %6s\n", repeat, "N", "former", "now",
              "ratio", "MB", "equal");
  for (const double target : sizes) {
    const PatchSet ps = bench::patched_to(bench::default_scene(), std::size_t(target), 0.05);
    const auto n = Eigen::Index(ps.size());
    PatchRgb B(n, 3), se(n, 3), var(n, 3);
    Rng rng = stream(1, StreamDomain::benchmark, 0, 0);
    for (Eigen::Index i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) {
        B(i, c) = rng.uniform();
        se(i, c) = 0.01 * rng.uniform() * B(i, c);
        var(i, c) = se(i, c) * se(i, c) * 64;
      }
    const std::vector<CellField> fields = {rgb_field("B", B), rgb_field("B_se", se), rgb_field("B_var", var)};
    const std::string now_path = (dir / "bench_csv_now.csv").string(), former_path = (dir / "bench_csv_former.csv").string();
    double t_now = 1e300, t_former = 1e300;
    for (long r = 0; r < repeat; ++r) {
      double c0 = cpu_seconds();
      {
        std::ofstream out(former_path, std::ios::binary);
        test::former_patch_csv_rows(out, ps, fields, "run");
      }
      t_former = std::min(t_former, cpu_seconds() - c0);
      c0 = cpu_seconds();
      write_patch_csv(now_path, ps, fields, "run");
      t_now = std::min(t_now, cpu_seconds() - c0);
    }
    std::ifstream a(now_path, std::ios::binary), b(former_path, std::ios::binary);
    std::string now((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>());
    const std::string former((std::istreambuf_iterator<char>(b)), std::istreambuf_iterator<char>());
    const bool equal = now.substr(now.find('\n') + 1) == former;
    std::printf("%10zu %12.3f %12.3f %8.2f %10.1f %6s\n", ps.size(), t_former, t_now, t_former / t_now,
                double(now.size()) / 1e6, equal ? "yes" : "NO");
    std::fflush(stdout);
    std::filesystem::remove(now_path);
    std::filesystem::remove(former_path);
  }
  return 0;
}
