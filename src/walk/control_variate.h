#pragma once
// The constant control variate of the gathering walks.
//
// For a constant c per channel, B - c 1 solves the same kind of system with a shifted source:
//   B = c 1 + B',   B' = E' + H B',   E' = E - c (1 - rho .* s),   s = F 1 (the row sums of F),
// because H (c 1) = c rho .* s. A walk that estimates B' from E' and adds c back estimates B without bias
// (the walks are linear in the source and take signed values), and where B is nearly constant E' is small, so
// the scores vary less. c is chosen without a pilot run as
//   c = sum_i A_i E_i / sum_i A_i (1 - rho_i s_i)
// per channel: the exact B when B is constant (Cohen's ambient term), and the value for which sum_i A_i E'_i = 0.
// Needs the row sums of F, so only with F stored (the matrix kernel). Docs: docs/theory/control_variate.md.
#include "core/types.h"
#include "solve/problem.h"

namespace radwalk {

struct ControlVariate {
  Rgb c = Rgb::Zero();  // the constant, per channel
  PatchRgb E_shifted;   // E' = E - c (1 - rho .* s)
};

// c and E' of `problem` (F stored, N x N).
ControlVariate constant_control_variate(const RadiosityProblem& problem);

}  // namespace radwalk
