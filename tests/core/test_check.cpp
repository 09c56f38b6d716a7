// RADWALK_CHECK macros and the "did you mean" matcher.
#include <catch2/catch.hpp>
#include <string>

#include "core/check.h"
#include "core/did_you_mean.h"

using namespace radwalk;

TEST_CASE("a failed check throws InternalError naming the expression, both operands and the line", "[check]") {
  const std::size_t rows = 3, patches = 4;
  try {
    RADWALK_CHECK_EQ(rows, patches);
    FAIL("no throw");
  } catch (const InternalError& e) {
    const std::string what = e.what();
    CHECK(what.find("tests/core/test_check.cpp:") == 0);
    CHECK(what.find("rows == patches") != std::string::npos);
    CHECK(what.find("left 3, right 4") != std::string::npos);
  }
  CHECK_THROWS_AS(RADWALK_CHECK(rows > patches), InternalError);
  CHECK_NOTHROW(RADWALK_CHECK_LT(rows, patches));
  CHECK_NOTHROW(RADWALK_CHECK(rows < patches));
}

TEST_CASE("edit distance counts insertions, deletions, substitutions and adjacent transpositions", "[check]") {
  CHECK(edit_distance("", "") == 0);
  CHECK(edit_distance("solve", "solve") == 0);
  CHECK(edit_distance("solv", "solve") == 1);
  CHECK(edit_distance("slove", "solve") == 1);  // transposition
  CHECK(edit_distance("Solve", "solve") == 0);  // case-insensitive
  CHECK(edit_distance("kitten", "sitting") == 3);
}

TEST_CASE("did you mean offers the nearest choice only when it is near", "[check]") {
  const std::vector<std::string> methods = {"gather-absorption", "gather-collision", "gather-expected-value",
                                            "shoot-collision", "shoot-absorption", "shoot-survival"};
  CHECK(nearest_choice("gather-colision", methods) == "gather-collision");
  CHECK(nearest_choice("shoot-survivl", methods) == "shoot-survival");
  CHECK(nearest_choice("xyz", methods).empty());
  CHECK(did_you_mean("xyz", methods).empty());
  CHECK(did_you_mean("solv", {"check", "patch", "formfactors", "solve", "compare", "pathtrace"}) ==
        " (did you mean 'solve'?)");
  // A unique prefix is offered; an ambiguous one is not.
  CHECK(nearest_choice("gauss", {"direct", "jacobi", "gauss-seidel", "southwell"}) == "gauss-seidel");
  CHECK(nearest_choice("gather", methods).empty());
}
