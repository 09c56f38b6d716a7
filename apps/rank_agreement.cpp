#include "apps/rank_agreement.h"

#include <string_view>

#include "core/distributed.h"
#include "core/error.h"

namespace radwalk::app {
namespace {

// The bytes exchanged: each string as its length in decimal, ':', then its bytes.
void put(std::string& out, std::string_view s) {
  out += std::to_string(s.size());
  out += ':';
  out += s;
}

// Reads one string written by put from `in` (advanced past it) into `s`; false when `in` holds none.
bool get(std::string_view& in, std::string& s) {
  const std::size_t colon = in.find(':');
  if (colon == std::string_view::npos || colon == 0 || colon > 19) return false;
  std::size_t n = 0;
  for (std::size_t k = 0; k < colon; ++k) {
    if (in[k] < '0' || in[k] > '9') return false;
    n = n * 10 + static_cast<std::size_t>(in[k] - '0');
  }
  if (in.size() - colon - 1 < n) return false;
  s.assign(in.substr(colon + 1, n));
  in.remove_prefix(colon + 1 + n);
  return true;
}

// A value from a command line fit for a one-line message: control characters become '?'.
std::string printable(std::string s) {
  for (char& c : s)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return s;
}

std::string encode(const RankCommand& c) {
  std::string out;
  put(out, c.program);
  put(out, c.command);
  put(out, c.refusal);
  for (const OptionSetting& o : c.options) {
    put(out, o.name);
    put(out, std::string(1, static_cast<char>('0' + static_cast<int>(o.kind))));
    put(out, o.given ? "1" : "0");
    put(out, o.value);
  }
  return out;
}

// False when `bytes` is not what encode writes.
bool decode(std::string_view bytes, RankCommand& c) {
  if (!get(bytes, c.program) || !get(bytes, c.command) || !get(bytes, c.refusal)) return false;
  while (!bytes.empty()) {
    OptionSetting o;
    std::string kind, given;
    if (!get(bytes, o.name) || !get(bytes, kind) || !get(bytes, given) || !get(bytes, o.value)) return false;
    if (kind.size() != 1 || kind[0] < '0' || kind[0] > '2') return false;
    o.kind = static_cast<OptionSetting::Kind>(kind[0] - '0');
    o.given = given == "1";
    c.options.push_back(std::move(o));
  }
  return true;
}

// Whether two settings of the same option compute the same: a file's presence; a flag's presence; a value as
// given or its default (an option without a default and not given is apart from every given value).
bool same_setting(const OptionSetting& a, const OptionSetting& b) {
  if (a.kind != b.kind) return false;
  if (a.kind != OptionSetting::Kind::value) return a.given == b.given;
  const bool a_set = a.given || !a.value.empty(), b_set = b.given || !b.value.empty();
  return a_set == b_set && a.value == b.value;
}

// An option setting as the message names it: "--seed 7", "--seed 3 (the default)", "--two-sided", "no --csv".
std::string shown(const OptionSetting& o) {
  const std::string name = printable(o.name);
  if (o.kind != OptionSetting::Kind::value) return o.given ? name : "no " + name;
  if (o.given) return name + " " + printable(o.value);
  if (!o.value.empty()) return name + " " + printable(o.value) + " (the default)";
  return "no " + name;
}

const char* const kSameCommand = " (every rank must run the same command with the same options)";

std::string encode(const RankInputs& inputs) {
  std::string out;
  put(out, inputs.refusal);
  for (const InputRead& f : inputs.files) {
    put(out, f.path);
    put(out, std::to_string(f.digest));
  }
  return out;
}

bool decode(std::string_view bytes, RankInputs& inputs) {
  if (!get(bytes, inputs.refusal)) return false;
  while (!bytes.empty()) {
    InputRead f;
    std::string digest;
    if (!get(bytes, f.path) || !get(bytes, digest) || digest.empty() || digest.size() > 20) return false;
    for (const char c : digest) {
      if (c < '0' || c > '9') return false;
      f.digest = f.digest * 10 + static_cast<std::uint64_t>(c - '0');
    }
    inputs.files.push_back(std::move(f));
  }
  return true;
}

// The agreement of every rank with rank 0 on what each describes as bytes: every rank receives rank 0's
// `mine`, and describe(rank 0's bytes) returns on each rank "" when it agrees, else one line naming the first
// difference; when any rank's line is not empty, every rank throws the InputError of the lowest such rank
// (distributed::agree_on_input_error). The collectives are one fixed sequence, the same on every rank
// whatever the descriptions (a broadcast of rank 0's length and bytes, an allgather of the lines' lengths,
// and of the lines when one is not empty), so ranks that disagree meet in it rather than wait in different
// collectives. describe must not throw. With one process it does nothing.
template <class Describe>
void agree_with_root(const std::string& mine, Describe&& describe) {
  if (distributed::size() == 1) return;
  std::vector<char> root(mine.begin(), mine.end());
  distributed::broadcast(root);
  const std::string root_bytes(root.begin(), root.end());
  distributed::agree_on_input_error([&] {
    const std::string difference = describe(root_bytes);
    if (!difference.empty()) throw InputError(difference);
  });
}

}  // namespace

std::string command_difference(const RankCommand& root, const RankCommand& mine, int rank) {
  const std::string r = std::to_string(rank);
  // Step 1: the same program, else nothing else can be compared.
  if (mine.program != root.program)
    return "MPI rank " + r + " runs " + printable(mine.program) + " but rank 0 runs " +
           printable(root.program);
  // Step 2: both command lines accepted (two refusals agree: each rank refuses its own), then the same
  // command.
  if (!mine.refusal.empty() && !root.refusal.empty()) return "";
  if (!mine.refusal.empty())
    return "MPI rank " + r + " refuses its command line, rank 0 does not: " + printable(mine.refusal);
  if (!root.refusal.empty())
    return "MPI rank 0 refuses its command line, rank " + r + " does not: " + printable(root.refusal);
  if (mine.command != root.command)
    return "MPI rank " + r + " runs '" + printable(mine.command) + "' but rank 0 runs '" +
           printable(root.command) + "'";
  // Step 3: the options, in the order declared (the same program declares the same ones).
  for (std::size_t k = 0; k < mine.options.size() || k < root.options.size(); ++k) {
    if (k >= mine.options.size() || k >= root.options.size() || mine.options[k].name != root.options[k].name)
      return "MPI rank " + r + " and rank 0 declare different options for '" + printable(root.command) +
             "' (different builds of radwalk " + printable(root.program) + "?)";
    if (!same_setting(mine.options[k], root.options[k]))
      return "MPI rank " + r + " has " + shown(mine.options[k]) + ", rank 0 has " + shown(root.options[k]) +
             kSameCommand;
  }
  return "";
}

void agree_on_command(const RankCommand& mine) {
  agree_with_root(encode(mine), [&](const std::string& root_bytes) -> std::string {
    RankCommand root;
    if (!decode(root_bytes, root))
      return "MPI rank " + std::to_string(distributed::rank()) +
             " cannot read rank 0's command (a different radwalk?)";
    return command_difference(root, mine, distributed::rank());
  });
}

std::string input_difference(const RankInputs& root, const RankInputs& mine, int rank) {
  const std::string r = std::to_string(rank);
  // Step 1: the files both read, in order: the first whose bytes differ.
  for (std::size_t k = 0; k < mine.files.size() && k < root.files.size(); ++k) {
    if (mine.files[k].digest == root.files[k].digest) continue;
    const std::string& p0 = root.files[k].path;
    const std::string& p = mine.files[k].path;
    return "MPI ranks 0 and " + r + " read different bytes from " +
           (p == p0 ? printable(p0)
                    : "the same input (" + printable(p0) + " on rank 0, " + printable(p) + " on rank " + r +
                          ")") +
           " (every rank must read the same inputs)";
  }
  // Step 2: a rank that refused its inputs (a file it lacks, bytes it could not parse) while the other did
  // not.
  if (!mine.refusal.empty() && !root.refusal.empty()) return "";
  if (!mine.refusal.empty())
    return "MPI rank " + r + " refuses its inputs, rank 0 does not: " + printable(mine.refusal);
  if (!root.refusal.empty())
    return "MPI rank 0 refuses its inputs, rank " + r + " does not: " + printable(root.refusal);
  // Step 3: a file one of them read and the other did not.
  if (mine.files.size() > root.files.size())
    return "MPI rank " + r + " read " + printable(mine.files[root.files.size()].path) + ", rank 0 did not";
  if (root.files.size() > mine.files.size())
    return "MPI rank 0 read " + printable(root.files[mine.files.size()].path) + ", rank " + r + " did not";
  return "";
}

void agree_on_inputs(const RankInputs& mine) {
  agree_with_root(encode(mine), [&](const std::string& root_bytes) -> std::string {
    RankInputs root;
    if (!decode(root_bytes, root))
      return "MPI rank " + std::to_string(distributed::rank()) +
             " cannot read rank 0's inputs (a different radwalk?)";
    return input_difference(root, mine, distributed::rank());
  });
}

}  // namespace radwalk::app
