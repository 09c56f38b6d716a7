#include "solve/response_spec.h"

#include <cmath>
#include <optional>
#include <sstream>
#include <unordered_map>

#include "core/csv_records.h"
#include "core/did_you_mean.h"
#include "core/error.h"
#include "core/input_file.h"
#include "mesh/text_scan.h"

namespace radwalk {
namespace {

// The pieces of s between separators (an empty last piece after a trailing separator).
std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(s);
  while (std::getline(in, part, sep)) parts.push_back(part);
  if (!s.empty() && s.back() == sep) parts.emplace_back();
  return parts;
}

// A patch number: the scene readers' integer rule (mesh/text_scan.h parse_long).
bool whole_number(const std::string& s, long& value) {
  const std::optional<long> v = parse_long(s);
  if (v) value = *v;
  return v.has_value();
}

// The name of an OBJ object or group in Mesh::groups' "object 'chair', group 'seat'" form: true if NAME is one
// of the quoted names.
bool group_has_name(const std::string& group, const std::string& name) {
  return group.find("'" + name + "'") != std::string::npos;
}

template <class Chosen>
Response select(const PatchSet& patches, const std::string& what, Chosen&& chosen) {
  Response r{Eigen::VectorXd::Zero(static_cast<Eigen::Index>(patches.size())), what};
  std::size_t count = 0;
  for (std::size_t i = 0; i < patches.size(); ++i)
    if (chosen(i)) r.R(static_cast<Eigen::Index>(i)) = 1, ++count;
  r.what = what + " (" + std::to_string(count) + (count == 1 ? " patch)" : " patches)");
  return r;
}

}  // namespace

std::vector<std::int32_t> patch_groups(const Mesh& mesh, const PatchSet& patches) {
  std::vector<std::int32_t> group_of_input;
  for (std::size_t f = 0; f < mesh.face_count() && f < mesh.face_group.size(); ++f) {
    const auto input = static_cast<std::size_t>(mesh.source_face(f));
    if (input >= group_of_input.size()) group_of_input.resize(input + 1, -1);
    group_of_input[input] = mesh.face_group[f];
  }
  std::vector<std::int32_t> group(patches.size(), -1);
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const auto f = static_cast<std::size_t>(patches.face[i]);
    if (f < group_of_input.size()) group[i] = group_of_input[f];
  }
  return group;
}

Eigen::VectorXd response_from_csv(const std::string& text, const std::string& file, const std::string& column,
                                  const std::string& spec, std::size_t patch_count) {
  const std::string context = " --response " + spec + ":";
  std::vector<CsvRecord> records;
  try {
    records = read_csv_records(text, file);
  } catch (const InputError& e) {  // "FILE:LINE: what" -> "FILE:LINE: --response SPEC: what"
    std::string m = e.what();
    const std::size_t at = m.find(": ", file.size());
    throw InputError(at == std::string::npos ? m : m.substr(0, at + 1) + context + m.substr(at + 1));
  }
  const std::vector<std::string> header = records.empty() ? std::vector<std::string>{""} : records[0].fields;
  const std::string at_header = file + ":1:" + context + " ";
  // Step 1: the header: every name once, a `patch` column and the weight column.
  std::unordered_map<std::string, std::size_t> column_of;
  for (std::size_t k = 0; k < header.size(); ++k)
    if (!column_of.emplace(header[k], k).second)
      throw InputError(at_header + "column '" + printable(header[k]) + "' is named twice (columns " +
                       std::to_string(column_of[header[k]] + 1) + " and " + std::to_string(k + 1) + ")");
  const auto patch_at = column_of.find("patch"), weight_at = column_of.find(column);
  if (patch_at == column_of.end()) throw InputError(at_header + "the CSV has no 'patch' column");
  if (weight_at == column_of.end())
    throw InputError(at_header + "no column '" + printable(column) + "'" + did_you_mean(column, header));
  const std::size_t patch_col = patch_at->second, weight_col = weight_at->second;
  // Step 2: the records (RFC 4180: quoted names may hold commas, quotes and line breaks): as many cells as the
  // header, a patch listed once, a finite weight.
  Eigen::VectorXd R = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(patch_count));
  std::vector<long> listed_on(patch_count, 0);  // the line that listed each patch, 0 if none
  for (std::size_t r = 1; r < records.size(); ++r) {
    const std::vector<std::string>& cells = records[r].fields;
    const long line_number = records[r].line;
    if (cells.size() == 1 && cells[0].empty()) continue;  // an empty line
    const std::string where = file + ":" + std::to_string(line_number) + ":" + context + " ";
    if (cells.size() != header.size())
      throw InputError(where + "the row has " + std::to_string(cells.size()) + " cells, the header " +
                       std::to_string(header.size()));
    long patch = 0;
    if (!whole_number(cells[patch_col], patch) || patch < 0 || std::size_t(patch) >= patch_count)
      throw InputError(where + "expected a patch number in [0, " + std::to_string(patch_count) + ") and a weight");
    if (const long first = listed_on[std::size_t(patch)])
      throw InputError(where + "patch " + std::to_string(patch) + " is listed twice (first on line " +
                       std::to_string(first) + ")");
    listed_on[std::size_t(patch)] = line_number;
    const std::string& cell = cells[weight_col];
    const ParsedNumber w = parse_number(cell);
    if (w.status == NumberStatus::out_of_range)
      throw InputError(where + "weight '" + printable(cell) + "' is out of range");
    if (w.status != NumberStatus::ok || !std::isfinite(w.value))
      throw InputError(where + "weight '" + printable(cell) + "' is not a number");
    R(patch) = w.value;
  }
  return R;
}

Response parse_response(const std::string& spec, const PatchSet& patches, const std::vector<std::int32_t>& group_of_patch,
                        const std::vector<std::string>& groups, const std::string& scene) {
  const std::size_t colon = spec.find(':');
  const std::string kind = spec.substr(0, colon), rest = colon == std::string::npos ? "" : spec.substr(colon + 1);
  const std::vector<std::string> kinds = {"patches", "material", "group", "csv"};
  if (colon == std::string::npos || rest.empty())
    throw InputError("--response '" + printable(spec) +
                     "': expected patches:I,J,..., material:NAME, group:NAME or csv:FILE:COLUMN");
  Response r;
  if (kind == "patches") {
    std::vector<char> on(patches.size(), 0);
    for (const std::string& p : split(rest, ',')) {
      long i = 0;
      if (!whole_number(p, i) || i < 0 || std::size_t(i) >= patches.size())
        throw InputError("--response " + printable(spec) + ": '" + printable(p) + "' is not a patch in [0, " +
                         std::to_string(patches.size()) + ")");
      on[std::size_t(i)] = 1;
    }
    r = select(patches, "patches " + rest, [&](std::size_t i) { return on[i] != 0; });
  } else if (kind == "material") {
    std::vector<std::string> names;
    int m = -1;
    for (std::size_t k = 0; k < patches.materials.size(); ++k) {
      names.push_back(patches.materials[k].name);
      if (patches.materials[k].name == rest) m = int(k);
    }
    if (m < 0)
      throw InputError("--response " + printable(spec) + ": no material '" + printable(rest) + "'" +
                       did_you_mean(rest, names));
    r = select(patches, "material '" + rest + "'", [&](std::size_t i) { return patches.material[i] == m; });
  } else if (kind == "group") {
    std::vector<char> in_group(groups.size(), 0);
    bool any = false;
    for (std::size_t g = 0; g < groups.size(); ++g) any |= (in_group[g] = group_has_name(groups[g], rest));
    if (!any)
      throw InputError("--response " + printable(spec) + ": no OBJ object or group '" + printable(rest) + "' in " +
                       scene);
    r = select(patches, "group '" + rest + "'", [&](std::size_t i) {
      const std::int32_t g = i < group_of_patch.size() ? group_of_patch[i] : -1;
      return g >= 0 && std::size_t(g) < in_group.size() && in_group[std::size_t(g)];
    });
  } else if (kind == "csv") {
    const std::size_t last = rest.rfind(':');
    if (last == std::string::npos || last == 0 || last + 1 == rest.size())
      throw InputError("--response " + printable(spec) + ": expected csv:FILE:COLUMN");
    const std::string file = rest.substr(0, last), column = rest.substr(last + 1);
    r = {response_from_csv(read_input_file(file), file, column, spec, patches.size()),
         "column '" + column + "' of " + file};
  } else {
    throw InputError("--response '" + printable(spec) + "': unknown kind '" + printable(kind) + "'" +
                     did_you_mean(kind, kinds) + "; expected patches:, material:, group: or csv:");
  }
  check_response(r, patches.size());
  return r;
}

}  // namespace radwalk
