// The ParaView state of a heat exchange (io/paraview_state.h, heat_flux_colouring): coloured by q with a diverging
// map symmetric about 0 and the unit in the bar's title; and through the CLI, `radwalk exchange --paraview-state`.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "io/paraview_state.h"

using namespace radwalk;

TEST_CASE("heat_flux_colouring: q with Cool to Warm over [-max |q|, max |q|] and W/m^2 in the title, in the state",
          "[io][paraview]") {
  const StateColouring c =
      heat_flux_colouring({-40.0, 12.5, std::numeric_limits<double>::quiet_NaN(), 586.0, -0.0});
  CHECK(c.field == "q");
  CHECK(c.lo == -586.0);
  CHECK(c.hi == 586.0);
  CHECK(c.preset == "Cool to Warm");
  CHECK(c.title.find("W/m^2") != std::string::npos);
  const StateColouring zero = heat_flux_colouring({0.0, 0.0});
  CHECK(zero.lo < zero.hi);

  const auto path = (std::filesystem::temp_directory_path() / "radwalk_heat_state.py").string();
  write_paraview_state(path, "heat.vtp", {}, c);
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  CHECK(s.find("field = 'q'") != std::string::npos);
  CHECK(s.find("ApplyPreset('Cool to Warm', True)") != std::string::npos);
  CHECK(s.find("value_range = [-586, 586]") != std::string::npos);
  CHECK(s.find("title = 'q [W/m^2] (net leaving)'") != std::string::npos);
  CHECK(s.find("Viridis") == std::string::npos);
  std::filesystem::remove(path);
}
