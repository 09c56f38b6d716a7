#include "walk/named_choice.h"

#include "core/did_you_mean.h"
#include "core/error.h"

namespace radwalk {

std::string join_names(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& name : names) s += (s.empty() ? "" : ", ") + name;
  return s;
}

void refuse_choice(std::string_view what, std::string_view given, const std::vector<std::string>& names) {
  const std::string g(given);
  throw InputError("random walk: unknown " + std::string(what) + " '" + g + "' (valid: " + join_names(names) + ")" +
                   did_you_mean(g, names));
}

}  // namespace radwalk
