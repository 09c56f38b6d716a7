#pragma once
// The failure hook of the statistical tests (as pbrt-v4 dumps its chi-square tables): when a hypothesis test
// rejects, the test writes what it compared (observed and expected tables as CSV; for scene tests with patches a
// .vtp of the per-patch z-scores, z = (estimate - expected) / se) into one folder and names the files in its
// failure message, so a failure can be looked at (a spreadsheet, ParaView) instead of re-run under a debugger.
//
// Folder: $RADWALK_TEST_ARTIFACTS when set, else test-artifacts/ in the build tree. File names: the running
// Catch2 test case and what the table holds, "<test case>--<what>.csv", with every character outside
// [A-Za-z0-9._-] replaced by '_' (e.g. "light_tracer__furnace_B___E____1_-_rho__on_every_patch--light-traced_
// furnace_B.csv"). Nothing is written while tests pass.
#include <filesystem>
#include <string>
#include <vector>

#include "core/types.h"
#include "patch/patch_set.h"

namespace radwalk::test {

std::filesystem::path artifact_dir();

// artifact_dir() / "<test case>--<what>.<extension>" (the folder is created); the path is also printed on stderr
// as one line "radwalk test artifact: PATH".
std::filesystem::path artifact_path(const std::string& what, const std::string& extension);

// A table of cells (already formatted) as CSV at artifact_path(what, "csv"); returns the path.
std::string write_artifact_csv(const std::string& what, const std::vector<std::string>& header,
                               const std::vector<std::vector<std::string>>& rows);

// A number for a table: 17 significant digits (round-trips), "nan" / "inf" as such.
std::string artifact_number(double v);

// The patches with the per-patch, per-channel estimate, its standard error, the expected value and z as cell
// data of a .vtp at artifact_path(what, "vtp") (NaN where an entry was not tested); returns the path.
std::string write_artifact_patch_z(const std::string& what, const PatchSet& patches, const PatchRgb& estimate,
                                   const PatchRgb& se, const PatchRgb& expected, const PatchRgb& z);

}  // namespace radwalk::test
