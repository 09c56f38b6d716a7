#include "mesh/repeated_corners.h"

#include <unordered_map>

namespace radwalk {

CornerLoops split_repeated_corners(const std::vector<std::int32_t>& ids) {
  CornerLoops out;
  std::vector<int> stack;                          // positions of the corners of the open outline
  std::unordered_map<std::int32_t, int> on_stack;  // id -> its depth on the stack
  for (int k = 0; k < static_cast<int>(ids.size()); ++k) {
    const std::int32_t id = ids[static_cast<std::size_t>(k)];
    const auto it = on_stack.find(id);
    if (it == on_stack.end()) {
      on_stack.emplace(id, static_cast<int>(stack.size()));
      stack.push_back(k);
      continue;
    }
    // The corners from the earlier visit up to here close a loop; the earlier visit stays for the rest.
    out.repeated = true;
    const auto depth = static_cast<std::size_t>(it->second);
    std::vector<int> loop(stack.begin() + static_cast<std::ptrdiff_t>(depth), stack.end());
    for (std::size_t d = depth + 1; d < stack.size(); ++d) on_stack.erase(ids[static_cast<std::size_t>(stack[d])]);
    stack.resize(depth + 1);
    out.loops.push_back(std::move(loop));
  }
  out.loops.push_back(std::move(stack));
  return out;
}

}  // namespace radwalk
