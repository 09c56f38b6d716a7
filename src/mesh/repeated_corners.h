#pragma once
// A face's outline split at its repeated corners into loops that repeat none, the readers' and validation's one
// rule for faces that name a corner twice (`f 1 2 2 3`, `f 1 2 3 1 4 5`, `f 1 2 1`).
//
// An outline c_0 c_1 ... c_(n-1) that visits corner v twice, at positions p < q, is two closed outlines: the loop
// c_p ... c_(q-1) and the rest, c_0 ... c_p c_(q+1) ... c_(n-1). Their vector areas add up to the outline's
// (Newell's sum 1/2 sum_k c_k x c_(k+1) splits term by term at the shared corner), so splitting keeps the area as
// drawn. Scanning once with a stack of the corners seen: when a corner repeats one on the stack, the corners
// above it close a loop and are popped. A consecutive repeat (`2 2`) closes a loop of one corner, a spike
// (`1 2 1`) one of two: neither has area. What remains on the stack at the end is the last loop (a repeat of the
// first corner at the end, `1 2 3 1`, closes a loop of one corner).
#include <cstdint>
#include <vector>

namespace radwalk {

struct CornerLoops {
  std::vector<std::vector<int>> loops;  // positions into the input (each loop in input order), every loop of any
                                        // size, the last one being the rest of the outline
  bool repeated = false;                // some corner was named twice
};

// The loops of an outline given by its corner ids (vertex indices, or welded ids). O(n) expected.
CornerLoops split_repeated_corners(const std::vector<std::int32_t>& ids);

}  // namespace radwalk
