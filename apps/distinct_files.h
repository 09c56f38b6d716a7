#pragma once
// No output overwrites an input or another output of the same run.
//
// A run reads its inputs (the scene, its MTL libraries, a --form-factors file) and writes its outputs (every output
// option, with the companions the writers add: the .mtl beside an .obj, the .se.exr beside an .exr). Two names are
// the same file when they resolve to the same path (symbolic links followed, "." and ".." removed) or, for files
// that exist, to the same inode (hard links). `--csv cube.obj`, `-o same.vtp --csv same.vtp` and a `patch -o
// shared.obj` whose shared.mtl is the scene's own library are refused before anything is written.
#include <string>
#include <vector>

namespace radwalk::app {

struct NamedFile {
  std::string role;  // what names it: "--csv", "-o", "the scene", "its material library"
  std::string path;
};

// The files an output option writes: `path` itself and its companions (.obj -> .mtl, .exr -> .se.exr).
std::vector<NamedFile> output_files_of(const std::string& role, const std::string& path);

// "" when every output is a different file from every input and every other output, else one line naming the two.
// Empty paths are skipped. "-" (standard output, core/standard_output.h) is no file: it is compared with nothing but
// another "-", and two outputs to standard output are refused ("--json - and --csv -: only one output can go to
// standard output; ...").
std::string check_distinct_files(const std::vector<NamedFile>& outputs, const std::vector<NamedFile>& inputs);

}  // namespace radwalk::app
