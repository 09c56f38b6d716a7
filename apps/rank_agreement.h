#pragma once
// What the ranks of an MPI run must agree on, checked before they compute anything together: every rank runs
// the whole command on its own copy of the inputs (core/distributed.h), so ranks that run different commands,
// options or inputs would wait in different collectives for ever, or put together parts of different
// computations.
//
// 1. The command (agree_on_command, at start-up, before any other collective): the same radwalk (version and
// git
//    describe), the same command and the same option values, each as given or its default (a value given
//    equal to the default agrees with the default). Per-rank options that do not change what is computed may
//    differ:
//    --threads (1 and N threads give bit-identical results) and --quiet (only rank 0 prints). Of the files,
//    only whether each was given must agree: the names of output files (only rank 0 writes), and those of the
//    input files (the scene, --form-factors), whose bytes are compared once read (2), so node-local copies at
//    different paths are accepted.
// 2. The inputs (agree_on_inputs, once the scene is read and validated): the digest of the bytes of every
// input
//    file in the order read (the scene, its material libraries, the --form-factors file: what the run id
//    hashes, apps/run_metadata.h), and whether reading them was refused.
// A disagreement is an InputError on every rank, one line naming the first difference and the ranks (exit 2):
//   MPI rank 1 runs 'formfactors' but rank 0 runs 'solve'
//   MPI rank 1 has --seed 7, rank 0 has --seed 3 (the default)
//   MPI ranks 0 and 1 read different bytes from scene.obj
// With one process both are no-ops.
#include <cstdint>
#include <string>
#include <vector>

namespace radwalk::app {

// One option of the command as a rank was given it.
struct OptionSetting {
  enum class Kind { value, flag, file };  // file: only whether it was given counts
  std::string name;                       // "--seed", or a positional's name ("scene")
  Kind kind = Kind::value;
  bool given = false;
  std::string value;  // the values as given, joined by spaces, else the default ("" when it has none)
};

// The command line of one rank.
struct RankCommand {
  std::string program;  // "radwalk VERSION (git describe)"
  std::string command;  // the command's name; "--help" or "--version" when asked for
  std::string refusal;  // the one-line refusal of this rank's command line, "" when it was accepted
  std::vector<OptionSetting> options;  // in the order the command declares them
};

// "" when `mine`, the command of rank `rank`, agrees with rank 0's (`root`), else the one line naming the
// first difference. Two refused command lines agree (each rank then refuses its own). Not collective.
std::string command_difference(const RankCommand& root, const RankCommand& mine, int rank);

// Collective, one fixed sequence of collectives whatever the commands: every rank compares its command with
// rank 0's; on any difference every rank throws the InputError of the lowest differing rank.
void agree_on_command(const RankCommand& mine);

// One input file as read.
struct InputRead {
  std::string path;          // as opened (the scene as given, its libraries relative to it)
  std::uint64_t digest = 0;  // Digest (core/digest.h) of its bytes
};

// The inputs of one rank: the files read, in order, and the refusal that ended the reading or validation, if
// any.
struct RankInputs {
  std::vector<InputRead> files;
  std::string refusal;
};

// "" when `mine`, the inputs of rank `rank`, agree with rank 0's (`root`): the same number of files with the
// same digests, in order, and both refused or neither (paths may differ). Else the one line naming the first
// file that differs (rank 0's path, and the other's when it differs) or the rank that refused alone. Not
// collective.
std::string input_difference(const RankInputs& root, const RankInputs& mine, int rank);

// Collective, one fixed sequence of collectives whatever the inputs: every rank compares its inputs with rank
// 0's; on any difference every rank throws the InputError of the lowest differing rank.
void agree_on_inputs(const RankInputs& mine);

}  // namespace radwalk::app
