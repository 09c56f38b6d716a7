#pragma once
// The files the commands write, and the names they accept. Every output option's file name must end in the
// extension of what is written there (so `solve -o out.png` cannot put VTK XML into a .png) and its directory must
// exist. radwalk.cpp checks every output option with check_output_file when it reads the command line, before
// anything is loaded or computed.
#include <string>

namespace radwalk::app {

enum class OutputFile {
  vtp,            // -o of solve, compare, pathtrace; --vtp of formfactors: VTK XML PolyData
  vtp_or_obj,     // -o of patch: VTK XML PolyData, or OBJ (+ .mtl)
  csv,            // --csv
  json,           // --json: the run summary (docs/json-schema.md)
  matrix_market,  // -o of formfactors
  image,          // --image of pathtrace: PNG (sRGB) or OpenEXR (linear)
};

// "" when `path` may be written as `kind` (an empty path is no output), else one line saying why not:
// "out.png: the file written is VTK XML PolyData, so its name must end in .vtp", the missing directory, or a path
// too long to open (core/path_length.h). "-" is standard output (core/standard_output.h) for csv and json, and
// refused for the others (it does not end in their extension).
// Extensions are compared exactly (".vtp", not ".VTP"): the writers choose their format by the same rule.
std::string check_output_file(const std::string& path, OutputFile kind);

// The accepted extensions for help texts: ".vtp", ".png|.exr".
std::string output_extensions(OutputFile kind);

// "" when `dir` may hold a --progressive series: a non-empty name (an empty one would write into the current
// directory) of a path short enough to open; else one line saying what is wrong (the parser prefixes the option).
std::string check_series_directory(const std::string& dir);

}  // namespace radwalk::app
