#pragma once
// Tables of named choices (the random-walk methods, kernels and survival rules): the one lookup of a name, whose
// refusal is one line that lists the valid names and suggests the nearest (core/did_you_mean.h), and the names
// as lists for help texts.
//
// A table is a std::array of rows, each with a `name` (std::string_view); the names of one table are distinct.
// NamedChoice is the row of a plain enum table (kernels, survival rules, walk directions), listed in enum order.
#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace radwalk {

template <class Enum>
struct NamedChoice {
  Enum value;
  std::string_view name;
  std::string_view help;  // for help texts
};

// True if row i of the table holds the enum value i (so that the table can be indexed by the enum).
template <class Enum, std::size_t N>
constexpr bool in_enum_order(const std::array<NamedChoice<Enum>, N>& rows) {
  for (std::size_t i = 0; i < N; ++i)
    if (static_cast<std::size_t>(rows[i].value) != i) return false;
  return true;
}

template <class Enum, std::size_t N>
constexpr std::string_view choice_name(const std::array<NamedChoice<Enum>, N>& rows, Enum value) {
  return rows[static_cast<std::size_t>(value)].name;
}

// "a, b, c": the names in table order.
std::string join_names(const std::vector<std::string>& names);

// Throws InputError "random walk: unknown WHAT 'given' (valid: a, b, c) (did you mean 'b'?)" (the last part only
// for a near miss).
[[noreturn]] void refuse_choice(std::string_view what, std::string_view given, const std::vector<std::string>& names);

template <class Row, std::size_t N>
std::vector<std::string> choice_names(const std::array<Row, N>& rows) {
  std::vector<std::string> names;
  for (const Row& row : rows) names.emplace_back(row.name);
  return names;
}

// The row named `given` (exact match); refuse_choice(what, ...) otherwise.
template <class Row, std::size_t N>
const Row& find_choice(const std::array<Row, N>& rows, std::string_view given, std::string_view what) {
  for (const Row& row : rows)
    if (row.name == given) return row;
  refuse_choice(what, given, choice_names(rows));
}

}  // namespace radwalk
