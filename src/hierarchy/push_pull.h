#pragma once
// Push-pull between the levels of an element tree (Hanrahan, Salzman and Aupperle 1991;
// docs/theory/hierarchical_radiosity.md, "Push-pull").
//
// Push: radiosity gathered at an element holds over the whole element, so each descendant receives it unchanged:
//   pushed_e = gathered_e + pushed_parent(e)        (top-down; pushed_root = gathered_root).
// The power a leaf ends with, A_l pushed_l, sums over the leaves to sum_e A_e gathered_e exactly in exact
// arithmetic, because the children of an element tile it (sum of the children's areas = the parent's area).
// Pull: a parent's radiosity is the area-weighted mean of its children's,
//   B_p = sum_c A_c B_c / sum_c A_c        (bottom-up),
// so A_p B_p = sum_c A_c B_c up to the rounding of the children's areas: the power at every level is the leaves'.
// Both run in O(elements), one pass in index order (children have larger indices than their parents).
#include <vector>

#include "core/types.h"
#include "hierarchy/element_tree.h"

namespace radwalk {

// values[e] += values[parent(e)] for every non-root e, top-down: afterwards values at the leaves are the sums of
// the gathered radiosities of their ancestors and themselves. values.size() == tree.size().
void push(const ElementTree& tree, std::vector<Rgb>& values);

// values[p] = area-weighted mean of values[children] for every non-leaf p, bottom-up (leaves unchanged).
void pull(const ElementTree& tree, std::vector<Rgb>& values);

// sum_e A_e values[e] over the elements e with `leaves_only` or every element otherwise (the power of a field).
Rgb power(const ElementTree& tree, const std::vector<Rgb>& values, bool leaves_only);

}  // namespace radwalk
