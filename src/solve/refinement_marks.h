#pragma once
// The patches (or leaves) to split by two first-order shares of the squared discretisation error Phi: where the
// error sits (the receiver share) and whose fluctuation causes it (the shooter share, solve/shooter_attribution.h)
// (docs/theory/discretisation_error.md, "Refinement by both shares").
//
// Each share ranks the elements on its own: for x = receiver (r_i >= 0) and x = shooter (c_j, only its positive
// part counts), the splittable elements in decreasing x are marked until the marked ones hold `fraction` of the
// total sum_i max(x_i, 0) (over every element, splittable or not), or the next x_i is at most `floor`. An element is
// split when either share marks it. The two shares are two first-order readings of the same Phi (sum_i r_i ~
// sum_j c_j ~ Phi): the receiver share is the gain of splitting i where i's error comes from its own extent (a
// shadow line across it), the shooter share the gain of splitting j where the error of what j lights comes from
// j's constant value (a bright patch whose first bounce varies within it, seen by a small receiver close by). The
// error is removed where either is right, so the union: each list alone is the plan's fraction of its own reading.
// At most `room` elements are split: when the union is larger, those with the largest max(r_i / R, c_i / C) (R, C
// the two totals) first. Ties: lower index first. With `shooter` empty the rule is the receiver rule alone.
#include <cstddef>
#include <vector>

namespace radwalk {

// One share's ranking, shared by refinement_marks and the groups' marks (solve/target_error.h,
// plan_group_targets): the elements in decreasing x (ties: lower index first) are held until the held ones' x
// reach `fraction` of sum_i max(x_i, 0), or the next x_i is at most `floor` (or 0), or an unmarked one would be the
// (room + 1)-th new mark: an element already in `marks` is held as it is (a split asked for by another reading of
// the error serves this one too); an unmarked splittable one is marked and held; an unmarked one not splittable is
// passed over. splittable: per element (empty: all). Returns the new marks.
std::size_t mark_largest(const std::vector<double>& x, double fraction, double floor,
                         const std::vector<bool>& splittable, std::size_t room, std::vector<bool>& marks);

// receiver: r_i (>= 0) per element; shooter: c_i per element or empty; splittable: per element (empty: all).
std::vector<bool> refinement_marks(const std::vector<double>& receiver, const std::vector<double>& shooter,
                                   double fraction, double floor, std::size_t room,
                                   const std::vector<bool>& splittable = {});

}  // namespace radwalk
