#pragma once
// The system's limits on path names: a path of at most PATH_MAX - 1 bytes (PATH_MAX counts the terminating NUL),
// each component (between slashes) at most NAME_MAX bytes. Longer paths cannot be opened (ENAMETOOLONG); radwalk
// refuses them up front, as bad input naming the path, for every input and output.
#include <string>

namespace radwalk {

// "" when `path` fits both limits, else one line: "PATH: path too long (N bytes; at most 4095)" or "PATH: path too
// long (a component of N bytes; at most 255 between slashes)". PATH is abbreviated to its first and last bytes
// when long, so the line stays readable.
std::string path_length_problem(const std::string& path);

// Throws InputError(path_length_problem(path)) when that is not "".
void require_path_length(const std::string& path);

}  // namespace radwalk
