#pragma once
// What the fuzz harnesses of tests/fuzz share: the oracles that hold for every reader (a one-line refusal
// naming the file, nothing but InputError), the oracles after a successful load and validation (finite
// positive areas, physical materials, patch areas adding up to their face's area), and the splitting of one
// fuzz input into several files.
//
// A broken oracle is a finding: fail() prints what broke to stderr and aborts, so that libFuzzer saves the
// input as a crash-* reproducer (and the replay executables of the normal build fail). Every harness is a
// LLVMFuzzerTestOneInput; the same source is built twice: with libFuzzer (RADWALK_FUZZ=ON, clang, ASan +
// UBSan) and, in the normal build, with replay_main.cpp, which runs it over the committed corpus.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>
#include <string_view>
#include <typeinfo>
#include <utility>
#include <vector>

#include "core/error.h"
#include "mesh/mesh.h"
#include "mesh/read_obj.h"
#include "patch/patch_set.h"

namespace radwalk::fuzz {

// Prints "fuzz oracle failed: WHAT" and aborts.
[[noreturn]] void fail(const std::string& what);

#define RADWALK_FUZZ_CHECK(condition, what)                                                         \
  do {                                                                                              \
    if (!(condition)) ::radwalk::fuzz::fail(std::string(#condition) + " does not hold: " + (what)); \
  } while (0)

// The fuzz input as text.
inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// Splits `input` at the first `separator`: the bytes before and after it (after is empty without a
// separator).
std::pair<std::string_view, std::string_view> split_at(std::string_view input, std::string_view separator);

// The separator between an OBJ and its MTL library in one fuzz input (a line of its own; see
// fuzz_obj_mtl.cpp).
inline constexpr std::string_view kMtlSeparator = "\n@@MTL@@\n";

// The material libraries of a fuzzed OBJ (read_obj_text): a resolved path without a space or tab holds the
// bytes `mtl` (which must outlive the MtlSource), one with a space or tab does not exist; every path read is
// appended to `files` (the files a message may name).
MtlSource fuzz_libraries(std::string_view mtl, std::vector<std::string>& files);

// Oracle (a) on a refusal: `message` is one line of printable, valid UTF-8 (no '\n', no control character, no
// DEL) that starts with one of `files` (as core/error.h's printable() writes it) followed by ':'.
void check_refusal_message(const std::string& message, const std::vector<std::string>& files);

// Runs body(). True when it returned; false when it threw an InputError whose message passes
// check_refusal_message(message, files) (files is read after body ran, so a body may add the files it
// opened). Any other exception (InternalError, NumericalError, std::bad_alloc, ...) is a finding.
template <class Body>
bool accepts(Body&& body, const std::vector<std::string>& files);

// What every reader's Mesh is, before validation: one material (-1 or an index) and one line per face,
// corners 0 to 2 non-negative and corner 3 a vertex or -1, finite vertices.
void check_read_mesh(const Mesh& mesh);

// Oracle (a) on the warnings of a mesh that was read (and validated): each is a message as
// check_refusal_message requires.
void check_warnings(const Mesh& mesh, const std::vector<std::string>& files);

// Oracle (b) after read + validate_mesh: every vertex is finite; faces exist; every corner is a vertex; every face has a finite
// positive area; every face has a material, and every material a face uses has rho = Kd finite in [0, 1) and
// an emission with Ke and E = pi * Ke finite and >= 0.
void check_validated_mesh(const Mesh& mesh);

// Oracle (b) after make_patches(mesh, max_edge) of a validated mesh: patches in face order, each face
// covered; every patch with the material, rho and E of its face, a finite non-negative area and a unit
// normal; the areas of a face's patches add up to the face's area within rounding plus twice the quad's area
// ambiguity (face_geometry.h; 0 for a planar quad), which validation keeps below its tolerance (checked too);
// with max_edge > 0 no patch edge is longer than max_edge (up to rounding); with max_edge <= 0
// patch f is face f, corner for corner.
void check_patches(const Mesh& mesh, const PatchSet& patches, double max_edge);

// -----------------------------------------------------------------------------------------------------------

template <class Body>
bool accepts(Body&& body, const std::vector<std::string>& files) {
  try {
    body();
    return true;
  } catch (const InputError& e) {
    check_refusal_message(e.what(), files);
    return false;
  } catch (const std::exception& e) {
    fail(std::string("an exception other than InputError: ") + typeid(e).name() + ": " + e.what());
  } catch (...) {
    fail("an exception that is not a std::exception");
  }
}

}  // namespace radwalk::fuzz
