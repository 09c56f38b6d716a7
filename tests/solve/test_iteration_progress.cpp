// IterationProgress: the total of an iterative solve is estimated from the rate at which its residual falls,
// kept between the iterations done and the budget; none (the iterations counted) before the residual falls.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "solve/iteration_progress.h"

using namespace radwalk;

namespace {

// Reports of a progress whose clock the test moves: one line per update (interval 1 s, the clock moves 2 s).
struct Lines {
  double t = 0;
  std::vector<std::string> text;
  ProgressOutput output() {
    return ProgressOutput::lines(1, [this] { return t; }, [this](const std::string& s) { text.push_back(s); });
  }
};

}  // namespace

TEST_CASE("iteration progress: the total follows the residual's rate, within the budget", "[solve][progress]") {
  Lines lines;
  {
    IterationProgress p("jacobi sweeps", 1e-10, 10000, lines.output());
    // r_k = 10^-k: 10 sweeps reach 1e-10; from r_1 = 0.1 at the same rate, the total is 1 + 9 = 10.
    for (long k = 1; k <= 4; ++k) {
      lines.t += 2;
      p.update(k, std::pow(10.0, -double(k)));
    }
    p.finish();
  }
  REQUIRE(lines.text.size() == 5);
  // Before a rate is known the budget is no length: the iterations are counted ("5 h 33 min left" before).
  CHECK(lines.text[0] == "radwalk: jacobi sweeps: 1 so far, 2.0 s elapsed\n");
  CHECK(lines.text[1].rfind("radwalk: jacobi sweeps 20% (2/10), 4.0 s elapsed", 0) == 0);
  CHECK(lines.text[3].rfind("radwalk: jacobi sweeps 40% (4/10), 8.0 s elapsed, about 12 s left", 0) == 0);
  CHECK(lines.text[4] == "radwalk: jacobi sweeps done in 8.0 s\n");

  // A residual that does not fall gives no total (the iterations counted); a budget below the estimate caps it.
  Lines flat;
  IterationProgress q("southwell shots", 1e-10, 50, flat.output());
  flat.t += 2;
  q.update(0, 1.0);
  flat.t += 2;
  q.update(10, 1.0);
  flat.t += 2;
  q.update(20, 0.5);  // 10 digits at 0.03 digits per shot: far beyond the budget of 50
  REQUIRE(flat.text.size() == 2);  // iteration 0 completes nothing, so it reports nothing
  CHECK(flat.text[0] == "radwalk: southwell shots: 10 so far, 4.0 s elapsed\n");
  CHECK(flat.text[1].rfind("radwalk: southwell shots 40% (20/50)", 0) == 0);
}
