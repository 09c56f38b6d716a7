#include "apps/command_line.h"

#include <algorithm>

#include "core/did_you_mean.h"
#include "mesh/text_scan.h"

namespace radwalk::app {
namespace {

// A number such as "-1" or "-0.5e3" (the number rule of mesh/text_scan.h, out of range included): a value, not
// an option.
bool is_number(const std::string& word) { return parse_number(word).status != NumberStatus::not_a_number; }

bool is_option(const std::string& word) { return word.size() > 1 && word[0] == '-' && !is_number(word); }

bool contains(const std::vector<std::string>& list, const std::string& word) {
  return std::find(list.begin(), list.end(), word) != list.end();
}

std::string unknown_option(const std::string& name, const std::vector<std::string>& known) {
  // Suggest long names for a long name, any name for "-long-name"; nothing for a one-letter name, for which
  // every other letter is as near.
  std::vector<std::string> candidates;
  for (const std::string& k : known)
    if (name.size() > 2 && (name.rfind("--", 0) != 0 || k.rfind("--", 0) == 0)) candidates.push_back(k);
  return "unknown option '" + name + "'" + did_you_mean(name, candidates);
}

const std::vector<std::string>& options_of(const CommandLineWords& words, const std::string& command) {
  static const std::vector<std::string> none;
  const auto it = words.options.find(command);
  return it == words.options.end() ? none : it->second;
}

std::string listed(const std::vector<std::string>& items) {
  std::string text;
  for (std::size_t k = 0; k < items.size(); ++k)
    text += (k == 0 ? "" : k + 1 == items.size() ? " or " : ", ") + items[k];
  return text;
}

}  // namespace

std::string selected_command(const std::vector<std::string>& args, const CommandLineWords& words) {
  for (std::size_t i = 1; i < args.size(); ++i) {
    if (args[i] == "--") return "";
    if (is_option(args[i])) continue;
    return contains(words.commands, args[i]) ? args[i] : "";
  }
  return "";
}

std::string unknown_word(const std::vector<std::string>& args, const CommandLineWords& words) {
  std::string command;
  std::size_t i = 1;
  for (; i < args.size() && command.empty(); ++i) {
    const std::string& word = args[i];
    if (is_option(word)) {
      const std::string name = word.substr(0, word.find('='));
      if (!contains(options_of(words, ""), name)) return unknown_option(name, options_of(words, ""));
      continue;
    }
    if (!contains(words.commands, word)) return "unknown command '" + word + "'" + did_you_mean(word, words.commands);
    command = word;
  }
  if (command.empty()) return "a command is required: " + listed(words.commands);
  const std::vector<std::string>& known = options_of(words, command);
  for (; i < args.size(); ++i) {
    const std::string& word = args[i];
    if (word == "--") break;
    if (!is_option(word)) continue;
    const std::string name = word.substr(0, word.find('='));
    if (!contains(known, name)) return unknown_option(name, known);
  }
  return "";
}

std::string unknown_choice(const std::string& given, const std::vector<std::string>& choices) {
  const std::string suggestion = did_you_mean(given, choices);
  if (!suggestion.empty()) return "unknown value '" + given + "'" + suggestion;
  return "unknown value '" + given + "' (expected one of " + listed(choices) + ")";
}

std::string help_pointer(const std::string& command) {
  return "see 'radwalk " + (command.empty() ? std::string() : command + " ") + "--help'";
}

}  // namespace radwalk::app
