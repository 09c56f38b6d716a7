#pragma once
// The scratch directory of a fuzz harness that must hand its input to a reader as a file (Matrix Market, .npz).
#include <filesystem>
#include <string>

namespace radwalk::fuzz {

// This process's scratch directory for a harness's temporary files, "radwalk-fuzz-HARNESS-PID" in $TMPDIR (else
// /dev/shm, else /tmp): created on the first call and removed at exit. One per process (the first name given).
const std::filesystem::path& scratch_directory(const std::string& harness);

}  // namespace radwalk::fuzz
