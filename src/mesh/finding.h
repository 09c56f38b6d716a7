#pragma once
// A finding: one thing the readers or validation found in a scene (a refusal, a repair, a warning or a note),
// structured so that `check` can print them grouped by kind and write them to JSON (docs/json-schema.md,
// key "findings").
//
// Every finding names where it is as far as known: the file and line, the input face (0-based, as the CSV's
// `face` column counts), and the face's OBJ object, group and material. A scene-wide finding has face -1.
// Validation collects every finding of a scene before it refuses (validate.h), so a user sees every defect in
// one run; MeshRefused carries them all.
#include <cstddef>
#include <string>
#include <vector>

#include "core/error.h"

namespace radwalk {

// How bad: error refuses the scene; repair changed it (refused with --strict); warning and note leave it as it
// is (a warning says something may be wrong, a note that something is harmless but worth knowing).
enum class Severity { note, warning, repair, error };

// "note", "warning", "repair", "error".
const char* severity_name(Severity severity);

struct Finding {
  std::string kind;        // what was found, the grouping key: "non-planar quad split", "bad vertex index", ...
  Severity severity = Severity::warning;
  std::string file;        // the file the line is in (the scene, or a material library)
  long line = 0;           // 1-based line, 0 if unknown or scene-wide
  long face = -1;          // input face (0-based), -1 if scene-wide
  std::string object, group, material;  // names as the file spells them, "" if none
  std::string message;     // what is wrong and what was done, one line, without file, line and face
  std::string stage = "read";  // who found it: "read" (a reader) or "validate" (validate_mesh)
};

// The finding as one line: "FILE:LINE: face F: MESSAGE (object 'o', group 'g', material 'm')" with the parts
// that are known, non-printable bytes escaped (core/error.h printable).
std::string finding_line(const Finding& finding);

// The findings of the given severities as lines grouped by kind (kinds in order of first appearance): the
// first `per_kind` of each kind as finding_line, then, when a kind has more, one line
// "FILE: KIND: N more (T in all)" where FILE is that kind's first finding's file.
std::vector<std::string> grouped_lines(const std::vector<Finding>& findings, const std::vector<Severity>& severities,
                                       std::size_t per_kind);

// "3 errors (2 bad vertex index, 1 duplicate face)": the count of the findings of one severity and their
// kinds ("" when there are none).
std::string count_by_kind(const std::vector<Finding>& findings, Severity severity);

// A scene refused after validation: what() is the first error's line and, if there were more, "; and N more
// errors (KINDS)" (one line); findings() holds every finding, errors and the rest.
class MeshRefused : public InputError {
 public:
  explicit MeshRefused(std::vector<Finding> findings);
  const std::vector<Finding>& findings() const { return findings_; }

 private:
  std::vector<Finding> findings_;
};

}  // namespace radwalk
