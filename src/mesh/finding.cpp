#include "mesh/finding.h"

#include <algorithm>

#include "core/excerpt.h"

namespace radwalk {

namespace {

std::string first_error_line(const std::vector<Finding>& findings) {
  const auto it = std::find_if(findings.begin(), findings.end(),
                               [](const Finding& f) { return f.severity == Severity::error; });
  if (it == findings.end()) return "the scene was refused";
  long errors = 0;
  for (const Finding& f : findings) errors += f.severity == Severity::error;
  std::string line = finding_line(*it);
  if (errors > 1) line += "; and " + std::to_string(errors - 1) + " more: " + count_by_kind(findings, Severity::error);
  return line;
}

}  // namespace

const char* severity_name(Severity severity) {
  switch (severity) {
    case Severity::note: return "note";
    case Severity::warning: return "warning";
    case Severity::repair: return "repair";
    case Severity::error: return "error";
  }
  return "?";
}

std::string finding_line(const Finding& f) {
  std::string context;
  if (!f.object.empty()) context = "object '" + excerpt(f.object) + "'";
  if (!f.group.empty()) context += (context.empty() ? "" : ", ") + ("group '" + excerpt(f.group) + "'");
  if (!f.material.empty()) context += (context.empty() ? "" : ", ") + ("material '" + excerpt(f.material) + "'");
  return locate(f.file, f.line, f.face, f.message + (context.empty() ? "" : " (" + printable(context) + ")"));
}

std::vector<std::string> grouped_lines(const std::vector<Finding>& findings, const std::vector<Severity>& severities,
                                       std::size_t per_kind) {
  auto wanted = [&](const Finding& f) {
    return std::find(severities.begin(), severities.end(), f.severity) != severities.end();
  };
  std::vector<std::string> kinds;  // in order of first appearance
  for (const Finding& f : findings)
    if (wanted(f) && std::find(kinds.begin(), kinds.end(), f.kind) == kinds.end()) kinds.push_back(f.kind);
  std::vector<std::string> lines;
  for (const std::string& kind : kinds) {
    std::size_t n = 0;
    const Finding* first = nullptr;
    for (const Finding& f : findings) {
      if (!wanted(f) || f.kind != kind) continue;
      if (!first) first = &f;
      if (n++ < per_kind) lines.push_back(finding_line(f));
    }
    if (n > per_kind)
      lines.push_back(locate(first->file, 0, -1,
                             kind + ": " + std::to_string(n - per_kind) + " more (" + std::to_string(n) + " in all)"));
  }
  return lines;
}

std::string count_by_kind(const std::vector<Finding>& findings, Severity severity) {
  std::vector<std::pair<std::string, long>> counts;
  long total = 0;
  for (const Finding& f : findings) {
    if (f.severity != severity) continue;
    ++total;
    auto it = std::find_if(counts.begin(), counts.end(), [&](const auto& c) { return c.first == f.kind; });
    if (it == counts.end())
      counts.emplace_back(f.kind, 1);
    else
      ++it->second;
  }
  if (total == 0) return "";
  std::string s = std::to_string(total) + " " + severity_name(severity) + (total == 1 ? "" : "s") + " (";
  for (std::size_t k = 0; k < counts.size(); ++k)
    s += (k ? ", " : "") + std::to_string(counts[k].second) + " " + counts[k].first;
  return s + ")";
}

MeshRefused::MeshRefused(std::vector<Finding> findings)
    : InputError(first_error_line(findings)), findings_(std::move(findings)) {}

}  // namespace radwalk
