#pragma once
// What the command-line parser (radwalk.cpp, CLI11) knows, in plain terms, and the one-line messages built from
// it for words it does not know: a mistyped command or option, an unknown value of a choice option. Kept apart
// from CLI11 (which costs seconds of compile per file) so the parser only describes its commands here.
#include <map>
#include <string>
#include <vector>

namespace radwalk::app {

// The command names, and per command every name of its options ("-o", "--output", "--max-edge", ...).
struct CommandLineWords {
  std::vector<std::string> commands;
  std::map<std::string, std::vector<std::string>> options;
};

// The command the arguments select: the first argument (after the program name) that is not an option, if it is
// a known command; "" otherwise.
std::string selected_command(const std::vector<std::string>& args, const CommandLineWords& words);

// The first word of the arguments the parser cannot know, as a message: "unknown command 'solv' (did you mean
// 'solve'?)", "unknown option '--max-egde' (did you mean '--max-edge'?)" (an option is taken up to '='; negative
// numbers are values, and everything after "--" is positional), or "a command is required (one of check, ...)"
// when no command is given; "" when every word is known.
std::string unknown_word(const std::vector<std::string>& args, const CommandLineWords& words);

// "unknown value 'gauss-seidl' (did you mean 'gauss-seidel'?)" or, without a near choice, "unknown value 'x'
// (expected one of a, b, c)".
std::string unknown_choice(const std::string& given, const std::vector<std::string>& choices);

// Where a parse error sends the reader: "see 'radwalk solve --help'" (or 'radwalk --help' without a command).
std::string help_pointer(const std::string& command);

}  // namespace radwalk::app
