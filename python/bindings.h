#pragma once
// The Python module `radwalk` (pybind11): a thin layer over the C++ library, with no computation of its own. Each
// file binds one concept; module.cpp ties them together:
//   scene_bindings.cpp        radwalk.load -> Scene (numpy views of the PatchSet; rho and E writable in place)
//   form_factor_bindings.cpp  radwalk.form_factors -> FormFactors (F as a scipy.sparse.csr_matrix, diagnostics)
//   solver_bindings.cpp       radwalk.solve -> Result (the deterministic solvers); the Result type
//   walk_bindings.cpp         radwalk.random_walk, radwalk.compare, radwalk.exact_variance
//   refine_bindings.cpp       radwalk.solve_adaptive -> AdaptiveResult (adaptive patching)
//   target_error_bindings.cpp radwalk.solve_to_target_error -> TargetErrorResult (accuracy on request)
//   measure_bindings.cpp      radwalk.measure -> Measurement (M = <R, B>_A by any method of `radwalk measure`)
//   exchange_bindings.cpp     radwalk.exchange -> Exchange (radiative heat exchange, solve/heat_exchange.h)
//   pathtrace_bindings.cpp    radwalk.pathtrace -> PathtraceResult (patch averages and images)
//   writer_bindings.cpp       radwalk.write_csv, write_vtp, write_matrix_market, read_form_factors
//   meshio_bindings.cpp       Scene.from_meshio, Result.to_meshio (Debian's python3-meshio, imported when called)
//   interruptible.cpp         Ctrl-C: computations run on a worker thread, signals are checked every 50 ms
//   arrays.h                  numpy views of C++ arrays and array arguments read into C++ (one set of conversions)
// Conventions: every computation runs without the GIL through interruptible() (KeyboardInterrupt within about
// 50 ms plus one chunk of work) under ThreadLimit(threads) (0 = all cores, at most kMaxThreads: check_run); the
// library's InputError becomes radwalk.InputError (a ValueError) carrying the CLI's one-line text,
// NumericalError radwalk.NumericalError (an ArithmeticError), InternalError radwalk.InternalError (a
// RuntimeError). A solve that diverged or was refused raises NumericalError with its message (check_solved), as
// the CLI exits 3.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "arrays.h"
#include "core/solution.h"
#include "core/types.h"
#include "formfactor/form_factors.h"
#include "mesh/mesh.h"
#include "patch/contact_patches.h"
#include "patch/patch_set.h"
#include "solve/problem.h"

namespace radwalk::python {

namespace py = pybind11;

// A loaded scene: the patches every computation works on, and what the CLI reports about them.
struct Scene {
  std::string path;
  double max_edge = 0;
  double max_area = 0;
  bool strict = false;
  std::string orient = "outward";     // --orient
  std::string open_shells = "auto";   // --open-shells
  double scale = 1;                   // --scale
  std::string unit;                   // --unit as given ("" for none)
  std::string length_unit = "mesh unit", radiosity_unit = "W per mesh unit^2";  // after scaling (length_unit.h)
  bool two_sided = false;    // every material two-sided (the CLI's --two-sided)
  bool contact_cut = true;   // cut the faces along contacts when they are split (--contact-cut, the default)
  bool cut = false;          // the faces were cut along contacts (contact_cut and a split)
  PatchSet patches;
  std::vector<std::int32_t> group;    // per patch: the group index of its input face, -1 outside any
  std::vector<std::string> groups;       // "object 'chair', group 'seat'" (what --response group:NAME matches)
  std::vector<std::string> group_names;  // the same groups as the user named them: "chair/seat", "chair", "seat"
  std::vector<std::string> warnings;  // validation's repairs and notices (the CLI's "radwalk: warning:" lines)
  std::vector<std::string> notes;     // validation's notes (the CLI's "note:" lines: what was read as it was meant)
  std::vector<ContactRegion> contact_regions;  // of the objects standing on faces (patch/contact_patches.h)
  // contact_cut, contacts found and the input faces kept as patches: the validated mesh, so that a computation that
  // splits the patches itself (solve_to_target_error) cuts them first, as the CLI's --target-error does.
  std::shared_ptr<const Mesh> uncut_mesh;
};

// The scene to split, for a scene whose uncut_mesh is set: the same mesh patched again with its supports cut along
// the contacts and the input faces otherwise kept (patch_scene's splits_later).
Scene cut_for_splitting(const Scene& scene);

// Form factors of one scene, as estimated (rays, escaped, back_hits filled) or read from Matrix Market (empty).
struct FormFactorsResult {
  FormFactors ff;
  std::vector<double> area;               // the scene's patch areas (for the diagnostics)
  std::map<std::string, double> timings;  // stage -> seconds, as the JSON's timings_s
  std::map<std::string, double> info;     // reciprocity change when enforced (the JSON's reciprocity_* keys)
};

// What a solver returns: the Solution, its stage timings, and the JSON metadata the CLI writes for it.
struct Result {
  Solution solution;
  std::map<std::string, double> timings;
  std::string metadata;  // a JSON object: the CLI's "solution" object and the run's options
};

// Scene.from_arrays (scene_bindings.cpp), the scene named `name` in messages: the FaceArrays of
// mesh/mesh_from_arrays.h from numpy arguments (vertices (V, 3); faces (F, k) or F lists; rho and emission (F, 3),
// (F,) or one number; groups None or F names), read, validated and patched as radwalk.load does a file.
Scene scene_from_arrays(const py::object& vertices, const py::object& faces, const py::object& rho,
                        const py::object& emission, const py::object& groups, bool two_sided, double max_edge,
                        double max_area, bool strict, bool contact_cut, const std::string& name);

// The checks before every computation on `scene`: `threads` from 0 to kMaxThreads (core/parallel.h, the CLI's
// bounds) and the scene's rho and E as a material could hold them (patch/radiometry_check.h check_radiometry: Scene.rho
// and Scene.E are writable). InputError naming the patch and value, or the thread count.
// Returns the thread count as the int ThreadLimit takes (within [0, kMaxThreads] once checked).
int check_run(const Scene& scene, long long threads);

// Raises NumericalError with the solver's message when it diverged or was refused (the CLI's exit code 3);
// "converged" and "max-iterations" (the CLI's exit 1) return.
void check_solved(const Solution& solution);

// The form factors a computation on `scene` uses: those of a FormFactors object, of a scipy.sparse matrix of any
// format or of a 2-D array (converted to float32 CSR: a copy), or, for None, estimated with `rays` rays per patch
// and `seed` (GIL released, timed into `timings` as "embree_scene" and "form_factors"). A matrix given by the
// caller is checked before scipy reads its structure: shape N x N, real values, index arrays of integers within
// [0, N) (and, compressed, an indptr of N + 1 non-decreasing offsets from 0), at most 2^31 - 1 entries, values
// finite and >= 0 (also after the conversion to float32). InputError naming what is wrong. With `sampling`, how
// F was traced (a FormFactors without its F: rays, options, emitter columns) when radwalk traced it (None or a
// FormFactors estimated by rays; empty rays otherwise), for its error (solve/form_factor_error.h).
SparseF form_factor_matrix(const py::object& F, const Scene& scene, long rays, std::uint64_t seed, int threads,
                           std::map<std::string, double>& timings, FormFactors* sampling = nullptr);

// Sets r.solution.B_disc, the estimated discretisation error (solve/discretisation_error.h), as the CLI's solve
// does with --discretisation-directions `directions` and --seed `seed` (0 directions: not estimated; a refused
// or failed solve: nothing), timed as "discretisation_error". Call with the GIL released.
void add_discretisation_error(Result& r, const Scene& scene, const RadiosityProblem& problem, int directions,
                              std::uint64_t seed);

// A Scene of refined patches (patch/refine.h: each keeps its input face) with everything else of `scene`: each
// patch's group is its input face's (refine_bindings.cpp).
Scene refined_scene(const Scene& scene, PatchSet patches);

// The metadata of a result as a JSON text: `run` (the options) plus the CLI's "solution" object, scene, max_edge,
// patches and timings_s.
std::string result_metadata(const Result& r, const Scene& scene, nlohmann::json run);

// A Python object from a JSON text (through Python's json module).
py::object json_to_python(const std::string& json_text);

void bind_scene(py::module_& m);
void bind_form_factors(py::module_& m);
void bind_solvers(py::module_& m);
void bind_walks(py::module_& m);
void bind_refinement(py::module_& m);
void bind_target_error(py::module_& m);
void bind_measure(py::module_& m);
void bind_pathtrace(py::module_& m);
void bind_exchange(py::module_& m);
void bind_writers(py::module_& m);
void bind_meshio(py::module_& m);  // after bind_scene and bind_solvers: adds to Scene and Result

}  // namespace radwalk::python
