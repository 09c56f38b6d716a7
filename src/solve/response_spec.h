#pragma once
// The response R of a measurement M = <R, B>_A (solve/measurement.h) from a text spec, as `radwalk measure
// --response SPEC` and radwalk.measure(response=SPEC) take it:
//   patches:I,J,...         those patches (0-based), weight 1
//   material:NAME           every patch of that material, weight 1
//   group:NAME              every patch of the OBJ object or group NAME (`o NAME` / `g NAME`), weight 1
//   csv:FILE:COLUMN         weight R_i from column COLUMN of a CSV with a `patch` column (response_from_csv)
// Unknown names get "did you mean"; an empty selection is an error.
#include <cstdint>
#include <string>
#include <vector>

#include "mesh/mesh.h"
#include "patch/patch_set.h"
#include "solve/measurement.h"

namespace radwalk {

// The OBJ object/group of every patch: an index into mesh.groups ("object 'chair', group 'seat'"), -1 outside
// any. PatchSet::face is the input face; the pieces of a repaired input face share its group.
std::vector<std::int32_t> patch_groups(const Mesh& mesh, const PatchSet& patches);

// group_of_patch: patch_groups(); groups: Mesh::groups; scene: the scene file (for messages). Throws InputError
// with a one-line message naming the spec and what is wrong; check_response holds for the result.
Response parse_response(const std::string& spec, const PatchSet& patches, const std::vector<std::int32_t>& group_of_patch,
                        const std::vector<std::string>& groups, const std::string& scene);

// The weights of column `column` of a CSV text (the contents of `file`) as radwalk writes them: a header line of
// comma-separated names, each once, then one record per row with as many cells as the header, read by RFC 4180
// (core/csv_records.h: a quoted cell, as radwalk writes a name holding a comma, a quote or a line break, may hold
// all three, quotes doubled, and span lines); a trailing '\r' (CRLF files) and blank lines are ignored. R_i = the weight of the row whose `patch`
// cell is i; each patch is listed at most once; patches the file does not list weigh 0. Every row must hold a
// whole patch number in [0, patch_count) and a finite number in the column, both under the scene readers' number
// rule (mesh/text_scan.h: parse_long, parse_number). Anything else is an InputError "FILE:LINE: --response SPEC:
// what is wrong" (line 1 for the header, the line a record starts on for a row).
Eigen::VectorXd response_from_csv(const std::string& text, const std::string& file, const std::string& column,
                                  const std::string& spec, std::size_t patch_count);

}  // namespace radwalk
