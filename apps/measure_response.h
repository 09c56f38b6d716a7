#pragma once
// The --response of `radwalk measure`: which patches a measurement M = <R, B>_A weighs (solve/measurement.h).
//   patches:I,J,...         those patches (0-based), weight 1
//   material:NAME           every patch of that material, weight 1
//   group:NAME              every patch of the OBJ object or group NAME (`o NAME` / `g NAME`), weight 1
//   csv:FILE:COLUMN         weight R_i from column COLUMN of a CSV with a `patch` column (as radwalk writes
//                           them); patches the file does not list weigh 0
// Unknown names get "did you mean"; an empty selection is an error.
#include <string>

#include "mesh/mesh.h"
#include "patch/patch_set.h"
#include "solve/measurement.h"

namespace radwalk::app {

// Throws InputError with a one-line message naming the spec and what is wrong.
Response parse_response(const std::string& spec, const Mesh& mesh, const PatchSet& patches);

}  // namespace radwalk::app
