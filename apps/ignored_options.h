#pragma once
// Options that the chosen method cannot honour, found at the command-line boundary and refused with one error
// ("--walk does not apply here (used only with --solver random-walk): remove it") instead of being dropped in
// silence or merely warned about: a run never differs from what its command line says.
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

// The messages (without the "radwalk: error: " prefix) for the options `command` cannot honour, one per rule.
std::vector<std::string> ignored_options(const SolveCommand& command, const OptionGiven& given);
std::vector<std::string> ignored_options(const FormFactorsCommand& command, const OptionGiven& given);
std::vector<std::string> ignored_options(const ExchangeCommand& command, const OptionGiven& given);
std::vector<std::string> ignored_options(const CompareCommand& command, const OptionGiven& given);
std::vector<std::string> ignored_options(const MeasureCommand& command, const OptionGiven& given);
std::vector<std::string> ignored_options(const PathtraceCommand& command, const OptionGiven& given);

}  // namespace radwalk::app
