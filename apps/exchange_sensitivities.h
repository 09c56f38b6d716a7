#pragma once
// radwalk exchange --sensitivities: dQ_G/d eps_H and dQ_G/d T_H between the groups of --group-by
// (solve/net_radiation_sensitivity.h), on the report, in the JSON (`exchange.sensitivities`) and with
// --sensitivities-csv as group_from,group_to,dQ_deps_W,dQ_dT_W_per_K.
#include <cstdint>
#include <string>
#include <vector>

#include "apps/run_metadata.h"
#include "formfactor/sparse_f.h"
#include "solve/net_radiation.h"

namespace radwalk::app {

// spec: "all" or a comma-separated list of group names (the response groups G). names: every group's name under
// group_by; group[i]: patch i's group. Throws InputError naming a response group that is not a group of the
// scene (with the first names it could be). error_note: why the sensitivities have no statistical error ("" never
// happens: the traced F's noise is not propagated into them).
void report_sensitivities(const std::string& spec, const std::string& csv, const std::string& group_by,
                          const NetRadiationInput& input, const SparseF& F, const NetRadiationResult& r,
                          const std::vector<std::int32_t>& group, const std::vector<std::string>& names,
                          bool traced, RunSummary& summary);

}  // namespace radwalk::app
