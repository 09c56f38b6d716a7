// The response specs of `radwalk measure --response` (solve/response_spec.h): the CSV reader on radwalk's own
// CSVs and on every malformed row, patches, materials and groups, and the one-line refusals.
#include <catch2/catch.hpp>
#include <string>

#include "core/error.h"
#include "patch/patch_builder.h"
#include "solve/response_spec.h"
#include "support/box_scenes.h"

using namespace radwalk;

namespace {

// The message of the InputError f throws ("" if none).
template <class F>
std::string refusal(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("response_from_csv: the weights of a column by the patch column", "[solve][response]") {
  // A CSV as radwalk writes it (a run_id column last, numbers in %.12g), rows in any order, a blank line.
  const std::string text =
      "patch,face,B_r,run_id\n"
      "2,1,0.25,d2db41ed9183ff0e\n"
      "0,0,1.5e-3,d2db41ed9183ff0e\n"
      "\n";
  const Eigen::VectorXd R = response_from_csv(text, "b.csv", "B_r", "csv:b.csv:B_r", 4);
  REQUIRE(R.size() == 4);
  CHECK(R(0) == 1.5e-3);
  CHECK(R(1) == 0);  // not listed: weight 0
  CHECK(R(2) == 0.25);
  CHECK(R(3) == 0);
  // CRLF line ends (a file edited on Windows) read the same.
  const Eigen::VectorXd crlf =
      response_from_csv("patch,w\r\n2,0.25\r\n0,1.5e-3\r\n", "b.csv", "w", "csv:b.csv:w", 4);
  CHECK(crlf == (Eigen::VectorXd(4) << 1.5e-3, 0, 0.25, 0).finished());
}

TEST_CASE("response_from_csv: names quoted by RFC 4180 (commas, quotes, line breaks) as radwalk's CSV writes them",
          "[solve][response]") {
  // The name columns of a radwalk CSV: a name holding a comma, a quote or a line break is quoted, quotes doubled
  // (io's CSV writer, docs/units-and-formats.md "Outputs"); the record of patch 1 spans two lines.
  const std::string text =
      "patch,face,object,group,material,B_r,run_id\n"
      "0,0,\"chair, left\",seat,wood,0.5,d2db41ed9183ff0e\n"
      "1,1,\"say \"\"hi\"\"\",\"two\nlines\",\"a,b\",0.25,d2db41ed9183ff0e\r\n"
      "2,2,,,\"\",0.125,d2db41ed9183ff0e\n";
  const Eigen::VectorXd R = response_from_csv(text, "b.csv", "B_r", "csv:b.csv:B_r", 3);
  CHECK(R == (Eigen::VectorXd(3) << 0.5, 0.25, 0.125).finished());
  // A column whose own name is quoted.
  CHECK(response_from_csv("patch,\"w, weighted\"\n1,2\n", "b.csv", "w, weighted", "csv:b.csv:w, weighted", 2) ==
        (Eigen::VectorXd(2) << 0, 2).finished());
  // Lines are counted across the quoted line break: the record after it starts on line 4.
  const auto refused = [](const std::string& t) {
    return refusal([&] { response_from_csv(t, "q.csv", "w", "csv:q.csv:w", 3); });
  };
  CHECK(refused("patch,name,w\n0,\"a\nb\",1\n7,x,1\n") ==
        "q.csv:4: --response csv:q.csv:w: expected a patch number in [0, 3) and a weight");
  // A quote that never closes, and text after a closing quote, are refused naming the line.
  CHECK(refused("patch,name,w\n0,x,1\n1,\"open,2\n") == "q.csv:3: --response csv:q.csv:w: a quoted field is never closed");
  CHECK(refused("patch,name,w\n0,\"a\"b,1\n") ==
        "q.csv:2: --response csv:q.csv:w: a closing quote must be followed by ',' or the end of the line");
}

TEST_CASE("response_from_csv: every malformed row is a one-line refusal naming file and line", "[solve][response]") {
  const auto refused = [](const std::string& text, const std::string& column) {
    return refusal([&] { response_from_csv(text, "w.csv", column, "csv:w.csv:" + column, 3); });
  };
  CHECK(refused("face,w\n0,1\n", "w") == "w.csv:1: --response csv:w.csv:w: the CSV has no 'patch' column");
  CHECK(refused("patch,weight\n0,1\n", "weigth").find("w.csv:1: --response csv:w.csv:weigth: no column 'weigth'") == 0);
  CHECK(refused("patch,weight\n0,1\n", "weigth").find("did you mean 'weight'") != std::string::npos);
  const std::string bad_patch = "expected a patch number in [0, 3) and a weight";
  CHECK(refused("patch,w\n0,1\n3,1\n", "w") == "w.csv:3: --response csv:w.csv:w: " + bad_patch);   // out of range
  CHECK(refused("patch,w\n-1,1\n", "w") == "w.csv:2: --response csv:w.csv:w: " + bad_patch);       // negative
  CHECK(refused("patch,w\n1.5,1\n", "w") == "w.csv:2: --response csv:w.csv:w: " + bad_patch);      // not whole
  CHECK(refused("patch,w\n1\n", "w") == "w.csv:2: --response csv:w.csv:w: the row has 1 cells, the header 2");
  CHECK(refused("patch,w\n1,abc\n", "w") == "w.csv:2: --response csv:w.csv:w: weight 'abc' is not a number");
  CHECK(refused("patch,w\n1,\n", "w") == "w.csv:2: --response csv:w.csv:w: weight '' is not a number");  // NaN cell
  CHECK(refused("patch,w\n1,2x\n", "w") == "w.csv:2: --response csv:w.csv:w: weight '2x' is not a number");
}

TEST_CASE("response_from_csv: a patch listed twice, a column named twice and ragged rows are refused",
          "[solve][response]") {
  const auto refused = [](const std::string& text, const std::string& column) {
    return refusal([&] { response_from_csv(text, "w.csv", column, "csv:w.csv:" + column, 3); });
  };
  const std::string at = "--response csv:w.csv:w: ";
  CHECK(refused("patch,w\n0,1\n2,3\n0,2\n", "w") == "w.csv:4: " + at + "patch 0 is listed twice (first on line 2)");
  CHECK(refused("patch,w,w\n0,1,2\n", "w") == "w.csv:1: " + at + "column 'w' is named twice (columns 2 and 3)");
  CHECK(refused("patch,x,patch\n0,1,2\n", "x") ==
        "w.csv:1: --response csv:w.csv:x: column 'patch' is named twice (columns 1 and 3)");
  CHECK(refused("patch,w\n0,1,5\n", "w") == "w.csv:2: " + at + "the row has 3 cells, the header 2");      // longer
  CHECK(refused("patch,w,x\n0,1,5\n1,2\n", "w") == "w.csv:3: " + at + "the row has 2 cells, the header 3");  // shorter
  CHECK(refused("patch,w\n0,1,\n", "w") == "w.csv:2: " + at + "the row has 3 cells, the header 2");  // trailing comma
  // The scene readers' number rule: hex floats are not numbers, overflow is out of range, underflow is 0.
  CHECK(refused("patch,w\n0,0x1p-1\n", "w") == "w.csv:2: " + at + "weight '0x1p-1' is not a number");
  CHECK(refused("patch,w\n0,1e400\n", "w") == "w.csv:2: " + at + "weight '1e400' is out of range");
  CHECK(refused("patch,w\n0,nan\n", "w") == "w.csv:2: " + at + "weight 'nan' is not a number");
  CHECK(response_from_csv("patch,w\n0,1e-400\n1,+0.5\n", "w.csv", "w", "csv:w.csv:w", 3) ==
        (Eigen::VectorXd(3) << 0, 0.5, 0).finished());
}

TEST_CASE("parse_response: patches, materials and groups", "[solve][response]") {
  PatchBuilder b;
  b.add_material("white", Rgb(0.5, 0.5, 0.5));
  const int red = b.add_material("red", Rgb(0.5, 0.1, 0.1));
  test::add_box(b, Vec3(0, 0, 0), Vec3(1, 1, 1), 1, true, 0);
  PatchSet p = b.build();
  p.material[3] = red;
  const std::vector<std::string> groups = {"group 'caps'", "object 'box', group 'walls'"};
  const std::vector<std::int32_t> group_of_patch = {1, 1, 0, 0, 1, -1};
  const auto parse = [&](const std::string& spec) { return parse_response(spec, p, group_of_patch, groups, "box.obj"); };

  const Response two = parse("patches:0,4");
  CHECK(two.R == (Eigen::VectorXd(6) << 1, 0, 0, 0, 1, 0).finished());
  CHECK(two.what == "patches 0,4 (2 patches)");
  CHECK(parse("material:red").R == (Eigen::VectorXd(6) << 0, 0, 0, 1, 0, 0).finished());
  CHECK(parse("material:red").what == "material 'red' (1 patch)");
  CHECK(parse("group:caps").R == (Eigen::VectorXd(6) << 0, 0, 1, 1, 0, 0).finished());
  CHECK(parse("group:box").R == (Eigen::VectorXd(6) << 1, 1, 0, 0, 1, 0).finished());  // the object's name too

  const auto refused = [&](const std::string& spec) { return refusal([&] { parse(spec); }); };
  CHECK(refused("patches:6") == "--response patches:6: '6' is not a patch in [0, 6)");
  CHECK(refused("material:rde").find("did you mean 'red'") != std::string::npos);
  CHECK(refused("group:lid") == "--response group:lid: no OBJ object or group 'lid' in box.obj");
  CHECK(refused("sensor:1").find("unknown kind 'sensor'") != std::string::npos);
  CHECK(refused("patches") == "--response 'patches': expected patches:I,J,..., material:NAME, group:NAME or csv:FILE:COLUMN");
  CHECK(refused("csv:w.csv") == "--response csv:w.csv: expected csv:FILE:COLUMN");
}
