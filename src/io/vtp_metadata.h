#pragma once
// VtpMetadata: what a .vtp file says about the run that made it, written as its field data (one 1-tuple array
// per entry: a string array for text, a double array for reals, a 64-bit integer array for integers), in the
// order the entries were set. Keys are array names, so they follow the rules of CellField names.
#include <cstdint>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace radwalk {

struct VtpMetadata {
  using Value = std::variant<std::string, double, std::int64_t>;
  std::vector<std::pair<std::string, Value>> entries;

  // Sets key to value, replacing an earlier value of the same key in place.
  void set(const std::string& key, Value value) {
    for (auto& [k, v] : entries)
      if (k == key) {
        v = std::move(value);
        return;
      }
    entries.emplace_back(key, std::move(value));
  }
  void set_text(const std::string& key, const std::string& text) { set(key, Value(text)); }
  void set_real(const std::string& key, double value) { set(key, Value(value)); }
  void set_integer(const std::string& key, std::int64_t value) { set(key, Value(value)); }
  // The value of key, or nullptr.
  const Value* find(const std::string& key) const {
    for (const auto& [k, v] : entries)
      if (k == key) return &v;
    return nullptr;
  }
  // Appends every entry of other (replacing keys already set).
  void merge(const VtpMetadata& other) {
    for (const auto& [k, v] : other.entries) set(k, v);
  }
};

}  // namespace radwalk
