// PYBIND11_MODULE(radwalk): the module's docstring, its exceptions and the bindings of every file (bindings.h).
#include <pybind11/pybind11.h>

#include "bindings.h"
#include "core/cancellation.h"
#include "core/error.h"
#include "core/parallel.h"
#include "patch/radiometry_check.h"
#include "core/progress.h"
#include "walk/walk_method.h"

namespace radwalk::python {

int check_run(const Scene& scene, long long threads) {
  check_thread_count(threads, "threads");
  check_radiometry(scene.patches);
  return static_cast<int>(threads);
}

void check_solved(const Solution& solution) {
  if (solution.status == SolveStatus::diverged || solution.status == SolveStatus::refused)
    throw NumericalError(solution.message.empty() ? solution.method + ": " + to_string(solution.status)
                                                  : solution.message);
}

py::object json_to_python(const std::string& json_text) {
  return py::module_::import("json").attr("loads")(json_text);
}

}  // namespace radwalk::python

using namespace radwalk;
using namespace radwalk::python;

PYBIND11_MODULE(radwalk, m) {
  // The example names a walk method through the method table (walk/walk_method.h), never spelled here.
  static const std::string module_doc = std::string(R"doc(radwalk: the radiosity equation B = E + diag(rho) F B on meshes, from Python.

A thin layer over radwalk's C++ library (the same code as the `radwalk` program, so the same seed gives the same
numbers, byte for byte in the CSV):

    import radwalk
    scene = radwalk.load("meshes/cube.obj")             # Scene: numpy views of the patches
    ff = radwalk.form_factors(scene, rays=1000, seed=1) # FormFactors: ff.F is a scipy.sparse.csr_matrix
    exact = radwalk.solve(scene, ff)                    # Result: exact.B is an N x 3 numpy array
    scene.rho[:] *= 0.9                                 # edit reflectances in place (or scene.set_material)
    walk = radwalk.random_walk(scene, ff, method=")doc" +
                                                    std::string(method_name(WalkMethod::gather_collision)) + R"doc(", walks_per_patch=1000, seed=1)
    radwalk.write_csv("cube.csv", scene, {**ff.diagnostics, **walk.fields})

Units as in the CLI: lengths in the mesh's unit, rho = Kd, E = pi * Ke, B in W per unit length squared.
Every computation releases the GIL and honours threads= (0: all cores; the output does not depend on it).
Bad input raises radwalk.InputError, a ValueError whose text is the CLI's one-line message (also for values
written into Scene.rho or Scene.E that a material could not hold, and for a malformed F); a solve that diverged or
was refused raises radwalk.NumericalError (an ArithmeticError) with the solver's message, where the CLI exits 3.
Ctrl-C interrupts a computation with KeyboardInterrupt within about 50 ms plus one chunk of its work. Progress lines go to stderr as in the CLI (set_progress).)doc");
  m.doc() = module_doc.c_str();
  m.attr("__version__") = RADWALK_VERSION;

  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<NumericalError> numerical_error(m, "NumericalError", PyExc_ArithmeticError);
  static py::exception<InternalError> internal_error(m, "InternalError", PyExc_RuntimeError);
  input_error.doc() = "Bad input (a file, a face, an option): the CLI's one-line message; a ValueError.";
  numerical_error.doc() = "A numerical failure a solver detected (singular or divergent system).";
  internal_error.doc() = "A broken internal invariant: a bug in radwalk, please report it.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      input_error(e.what());
    } catch (const NumericalError& e) {
      numerical_error(e.what());
    } catch (const InternalError& e) {
      internal_error(e.what());
    } catch (const Cancelled&) {  // a computation stopped by another thread's Ctrl-C (interruptible.h)
      PyErr_SetNone(PyExc_KeyboardInterrupt);
    }
  });

  m.def("set_progress", &Progress::set_enabled, py::arg("enabled"),
        "Turns the progress lines on stderr on or off (enabled: bool; the CLI's -q is set_progress(False)); on by "
        "default.");
  m.def("walk_methods", &walk_method_names,
        "The random-walk methods' names (a list of str), in the order of the one method table "
        "(src/walk/walk_method.h).");

  bind_scene(m);
  bind_form_factors(m);
  bind_solvers(m);
  bind_walks(m);
  bind_refinement(m);
  bind_target_error(m);
  bind_measure(m);
  bind_pathtrace(m);
  bind_exchange(m);
  bind_writers(m);
  bind_meshio(m);
}
