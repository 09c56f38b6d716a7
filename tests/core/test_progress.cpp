// Progress reports: plain lines at a fixed interval when stderr is not a terminal, nothing for quick stages,
// redrawn in place on a terminal, silent when disabled. A fake clock and a captured output replace time and stderr.
#include <catch2/catch.hpp>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/progress.h"

using namespace radwalk;

namespace {

// A clock the test moves by hand and the text a Progress printed.
struct FakeOutput {
  double t = 100;
  std::vector<std::string> written;

  ProgressOutput lines(double interval) {
    return ProgressOutput::lines(
        interval, [this] { return t; }, [this](const std::string& s) { written.push_back(s); });
  }
};

}  // namespace

TEST_CASE("progress: a line every interval with percentage and time left, then a done line", "[progress]") {
  FakeOutput out;
  {
    Progress p("form factors", 2938, out.lines(5));
    out.t += 1;
    p.advance(100);  // before the first interval: nothing
    CHECK(out.written.empty());
    out.t += 11;     // 12 s elapsed
    p.advance(1134);
    REQUIRE(out.written.size() == 1);
    CHECK(out.written[0] == "radwalk: form factors 42% (1234/2938), 12 s elapsed, about 17 s left\n");
    out.t += 1;
    p.advance(10);   // within the interval after the last report: nothing
    CHECK(out.written.size() == 1);
    out.t += 5;
    p.advance(10);
    CHECK(out.written.size() == 2);
    out.t += 2;
    p.advance(1584);
  }  // the destructor finishes
  REQUIRE(out.written.size() == 3);
  CHECK(out.written[2] == "radwalk: form factors done in 20 s\n");
}

TEST_CASE("progress: a stage that ends within the first interval prints nothing", "[progress]") {
  FakeOutput out;
  Progress p("reading form factors", 10, out.lines(5));
  for (int k = 0; k < 10; ++k) {
    out.t += 0.4;
    p.advance(1);
  }
  p.finish();
  p.finish();
  CHECK(out.written.empty());
}

TEST_CASE("progress: a long single work item still leaves its done line", "[progress]") {
  FakeOutput out;
  Progress p("LU factorisations", 1, out.lines(5));
  out.t += 30;
  p.finish();
  REQUIRE(out.written.size() == 1);
  CHECK(out.written[0] == "radwalk: LU factorisations done in 30 s\n");
}

TEST_CASE("progress: disabled prints nothing, in place redraws one line", "[progress]") {
  FakeOutput out;
  {
    ProgressOutput o = out.lines(1);
    o.enabled = false;
    Progress p("x", 4, o);
    out.t += 10;
    p.advance(2);
    p.finish();
  }
  CHECK(out.written.empty());

  ProgressOutput o = out.lines(1);
  o.in_place = true;
  Progress p("rendering", 100, o);
  out.t += 2;
  p.advance(50);
  out.t += 2;
  p.advance(50);
  p.finish();
  REQUIRE(out.written.size() == 3);
  CHECK(out.written[0] == "\rradwalk: rendering 50% (50/100), 2.0 s elapsed, about 2.0 s left");
  CHECK(out.written[1].rfind("\rradwalk: rendering 100% (100/100), 4.0 s elapsed", 0) == 0);
  // The done line overwrites the longer progress line and ends it.
  CHECK(out.written[2].rfind("\rradwalk: rendering done in 4.0 s ", 0) == 0);
  CHECK(out.written[2].size() == out.written[1].size() + 1);
  CHECK(out.written[2].back() == '\n');
}

TEST_CASE("progress: the total may be re-estimated while running", "[progress]") {
  FakeOutput out;
  Progress p("gauss-seidel sweeps", 100, out.lines(1));
  out.t += 2;
  p.set_total(20);
  p.advance(5);
  REQUIRE(out.written.size() == 1);
  CHECK(out.written[0] == "radwalk: gauss-seidel sweeps 25% (5/20), 2.0 s elapsed, about 6.0 s left\n");
}

TEST_CASE("progress: durations read as seconds, minutes or hours", "[progress]") {
  CHECK(Progress::format_duration(3.21) == "3.2 s");
  CHECK(Progress::format_duration(42.4) == "42 s");
  CHECK(Progress::format_duration(185) == "3 min 05 s");
  CHECK(Progress::format_duration(2 * 3600 + 7 * 60) == "2 h 07 min");
  CHECK(Progress::format("x", 0, 10, 1) == "x 0% (0/10), 1.0 s elapsed");
}

TEST_CASE("progress: a stage ended by an exception prints no done line", "[progress]") {
  FakeOutput out;
  try {
    Progress p("reading form factors", 10, out.lines(1));
    out.t += 2;
    p.advance(1);
    out.t += 2;
    throw std::runtime_error("bad line");
  } catch (const std::runtime_error&) {
  }
  REQUIRE(out.written.size() == 1);
  CHECK(out.written[0].find("done") == std::string::npos);
}

TEST_CASE("progress: stages sharing their silence report one interval after the last line of any of them",
          "[progress]") {
  FakeOutput out;
  ProgressOutput a_out = out.lines(5), b_out = out.lines(5), c_out = out.lines(5), alone = out.lines(5);
  const auto silence = std::make_shared<ProgressSilence>();
  a_out.silence = b_out.silence = c_out.silence = silence;
  {
    Progress a("form factors", 4, a_out);  // starts at 100, the silence's origin
    for (int k = 0; k < 4; ++k) {
      out.t += 1;
      a.advance(1);
    }
  }  // 4 s: too short to report on its own
  CHECK(out.written.empty());
  {
    Progress lone("alone", 4, alone);  // not sharing: its own first interval, from 104
    out.t += 1.5;                      // 105.5: 5.5 s of silence, 1.5 s of its own
    lone.advance(1);
    CHECK(out.written.empty());
  }
  Progress b("error propagation", 10, b_out);  // starts at 105.5, 5.5 s after the origin: due at once
  out.t += 0.5;
  b.advance(1);
  REQUIRE(out.written.size() == 1);
  CHECK(out.written[0] == "radwalk: error propagation 10% (1/10), 0.5 s elapsed, about 4.5 s left\n");
  b.advance(9);
  b.finish();  // 106: the done line, the last line
  REQUIRE(out.written.size() == 2);
  out.t += 3;
  Progress c("discretisation error estimate", 10, c_out);  // 109: due at 111, 5 s after the last line
  out.t += 1.5;
  c.advance(1);
  CHECK(out.written.size() == 2);
  out.t += 0.6;  // 111.1
  c.advance(1);
  REQUIRE(out.written.size() == 3);
  CHECK(out.written[2] == "radwalk: discretisation error estimate 20% (2/10), 2.1 s elapsed, about 8.4 s left\n");
}
