#pragma once
// Options that the chosen method ignores, found at the command-line boundary and reported as warnings
// ("--walk is ignored (used only with --solver random-walk)") instead of being dropped in silence.
//
// One table per command (ignored_options.cpp) says which options apply under which condition; an option given
// on the command line whose first failing condition is found there is reported, options of one row in one line.
// Adding an option or a condition is one table row.
#include <functional>
#include <string>
#include <vector>

#include "apps/options.h"

namespace radwalk::app {

// given(name): whether the option named "--name" was on the command line.
using OptionGiven = std::function<bool(const std::string& name)>;

// The warnings (without the "radwalk: warning: " prefix) for the options `command` ignores.
std::vector<std::string> ignored_options(const SolveCommand& command, const OptionGiven& given);
std::vector<std::string> ignored_options(const FormFactorsCommand& command, const OptionGiven& given);
std::vector<std::string> ignored_options(const CompareCommand& command, const OptionGiven& given);
std::vector<std::string> ignored_options(const PathtraceCommand& command, const OptionGiven& given);

}  // namespace radwalk::app
