// radwalk.form_factors and the FormFactors type: F as a scipy.sparse.csr_matrix viewing the library's CSR arrays.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "bindings.h"
#include "formfactor/emitter_form_factors.h"
#include "core/error.h"
#include "interruptible.h"
#include "core/parallel.h"
#include "core/timer.h"
#include "formfactor/analytic_form_factors.h"
#include "formfactor/form_factor_diagnostics.h"
#include "formfactor/reciprocity.h"
#include "visibility/embree_visibility.h"

namespace radwalk::python {
namespace {

// F (compressed) as scipy.sparse.csr_matrix((data, indices, indptr)) with views of its three arrays.
py::object csr_view(const SparseF& F, py::handle base) {
  const auto n = static_cast<std::size_t>(F.rows());
  const auto nnz = static_cast<std::size_t>(F.nonZeros());
  const py::object data = view(F.valuePtr(), nnz, 1, base), indices = view(F.innerIndexPtr(), nnz, 1, base),
                   indptr = view(F.outerIndexPtr(), n + 1, 1, base);
  return py::module_::import("scipy.sparse")
      .attr("csr_matrix")(py::make_tuple(data, indices, indptr), py::arg("shape") = py::make_tuple(n, F.cols()),
                          py::arg("copy") = false);
}

// F by cosine rays with `options`, then the emitter columns of choose_emitter_samples(emitter_request) (as the
// CLI's form-factor stage, apps/pipeline.cpp).
FormFactors estimate(const Scene& scene, const FormFactorOptions& options, long emitter_request, int threads,
                     std::map<std::string, double>& timings) {
  check_thread_count(threads, "threads");
  return interruptible([&] {
    ThreadLimit limit(threads);
    Timer timer;
    const EmbreeVisibility visibility(scene.patches);
    timings["embree_scene"] = timer.seconds();
    timer.reset();
    FormFactors ff = estimate_form_factors_with_emitters(scene.patches, visibility, options, emitter_request);
    timings["form_factors"] = timer.seconds();
    return ff;
  });
}

// emitter_columns as Python gives it: "auto" (or None) -> kAutoEmitterSamples, an int >= 0 as is.
long emitter_request(const py::object& emitter_columns) {
  if (emitter_columns.is_none()) return kAutoEmitterSamples;
  if (py::isinstance<py::str>(emitter_columns)) {
    if (emitter_columns.cast<std::string>() == "auto") return kAutoEmitterSamples;
  } else if (py::isinstance<py::int_>(emitter_columns) && !py::isinstance<py::bool_>(emitter_columns)) {
    const long long m = emitter_columns.cast<long long>();
    if (m >= 0 && m <= (1LL << 30)) return static_cast<long>(m);
  }
  throw InputError("emitter_columns must be 'auto' or an int in [0, 2^30], got " +
                   py::repr(emitter_columns).cast<std::string>());
}

// --- A caller's F, checked before scipy reads its structure ---------------------------------------------------
// scipy.sparse checks neither the range of a matrix's indices nor the order of its indptr, and its conversions
// (tocsr, sum_duplicates) index memory by them: a bad index reads or writes outside the arrays. So the arrays are
// read here first, as int64 (a wider index type would wrap), and the conversion happens only when they are sound.

template <class T>
using CArray = py::array_t<T, py::array::c_style | py::array::forcecast>;

constexpr std::int64_t kMaxEntries = std::numeric_limits<std::int32_t>::max();  // F's CSR uses 32-bit offsets

std::string dtype_text(const py::object& array) { return py::str(array.attr("dtype")).cast<std::string>(); }

// `array` (an attribute of F named `what`) as a 1-D int64 array; InputError unless it holds integers that fit.
CArray<std::int64_t> index_array(const py::object& array, const std::string& what) {
  const py::module_ np = py::module_::import("numpy");
  const py::object a = np.attr("asarray")(array);
  if (!np.attr("issubdtype")(a.attr("dtype"), np.attr("integer")).cast<bool>())
    throw InputError("F." + what + " must hold integers, not " + dtype_text(a));
  if (a.attr("ndim").cast<int>() != 1) throw InputError("F." + what + " must be a 1-D array");
  if (a.attr("dtype").attr("kind").cast<std::string>() == "u" && a.attr("size").cast<long long>() > 0 &&
      a.attr("max")().cast<py::int_>() > py::int_(std::numeric_limits<std::int64_t>::max()))
    throw InputError("F." + what + " holds a value above 2^63 - 1");
  return a.cast<CArray<std::int64_t>>();
}

// Refuses a value dtype that is not real (complex, object, strings) and values that are not finite or negative.
void check_values(const py::object& data, std::int64_t count) {
  const py::module_ np = py::module_::import("numpy");
  const py::array a = real_array(data, "F's values must be real numbers", "F's values must be real numbers, not");
  const auto v = np.attr("ravel")(a).cast<CArray<double>>();
  if (count > v.size()) throw InputError("F has fewer values than entries");
  for (std::int64_t k = 0; k < count; ++k)
    if (!(std::isfinite(v.data()[k]) && v.data()[k] >= 0))
      throw InputError("F holds the value " + number_text(v.data()[k]) + " (entry " + std::to_string(k) +
                       " of its data): form factors must be finite and >= 0");
}

// Compressed storage (CSR over rows, CSC over columns, BSR over blocks): `major` offsets + 1 in indptr, from 0,
// non-decreasing, the last (the entry count) at most the length of indices and data; indices in [0, minor).
// Each entry holds `values_per_entry` values (BSR: a block).
void check_compressed(const py::object& F, std::int64_t major, std::int64_t minor, const std::string& over,
                      std::int64_t values_per_entry = 1) {
  const CArray<std::int64_t> indptr = index_array(F.attr("indptr"), "indptr");
  const CArray<std::int64_t> indices = index_array(F.attr("indices"), "indices");
  if (indptr.size() != major + 1)
    throw InputError("F.indptr has " + std::to_string(indptr.size()) + " offsets; " + std::to_string(major + 1) +
                     " expected (one per " + over + ", plus one)");
  const std::int64_t* p = indptr.data();
  if (p[0] != 0) throw InputError("F.indptr starts at " + std::to_string(p[0]) + ", not 0");
  for (std::int64_t r = 0; r < major; ++r)
    if (p[r + 1] < p[r])
      throw InputError("F.indptr decreases at " + over + " " + std::to_string(r) + " (" + std::to_string(p[r]) +
                       " then " + std::to_string(p[r + 1]) + ")");
  const std::int64_t count = p[major];
  if (count > indices.size())
    throw InputError("F.indptr ends at " + std::to_string(count) + " but F.indices has only " +
                     std::to_string(indices.size()) + " entries");
  if (count > kMaxEntries) throw InputError("F has more than 2^31 - 1 entries");
  for (std::int64_t k = 0; k < count; ++k)
    if (indices.data()[k] < 0 || indices.data()[k] >= minor)
      throw InputError("F.indices[" + std::to_string(k) + "] = " + std::to_string(indices.data()[k]) +
                       " is outside [0, " + std::to_string(minor) + ")");
  const std::int64_t data_length = py::len(F.attr("data"));
  if (data_length < count)
    throw InputError("F.data has " + std::to_string(data_length) + " entries for " + std::to_string(count));
  check_values(F.attr("data"), count * values_per_entry);
}

// Coordinate storage: row, col and data of equal lengths, every index in [0, n).
void check_coordinates(const py::object& coo, std::int64_t n) {
  const CArray<std::int64_t> row = index_array(coo.attr("row"), "row"), col = index_array(coo.attr("col"), "col");
  const std::int64_t count = py::len(coo.attr("data"));
  if (row.size() != count || col.size() != count)
    throw InputError("F.row, F.col and F.data differ in length (" + std::to_string(row.size()) + ", " +
                     std::to_string(col.size()) + ", " + std::to_string(count) + ")");
  if (count > kMaxEntries) throw InputError("F has more than 2^31 - 1 entries");
  for (std::int64_t k = 0; k < count; ++k)
    if (row.data()[k] < 0 || row.data()[k] >= n || col.data()[k] < 0 || col.data()[k] >= n)
      throw InputError("F's entry " + std::to_string(k) + " at (" + std::to_string(row.data()[k]) + ", " +
                       std::to_string(col.data()[k]) + ") is outside [0, " + std::to_string(n) + ")^2");
  check_values(coo.attr("data"), count);
}

// A scipy call on a checked matrix; the ValueError or TypeError it may still raise (a malformed object scipy
// itself refuses) becomes InputError.
template <class Call>
py::object scipy_call(const std::string& what, Call&& call) {
  try {
    return call();
  } catch (const py::error_already_set& e) {
    if (!e.matches(PyExc_ValueError) && !e.matches(PyExc_TypeError) && !e.matches(PyExc_IndexError) &&
        !e.matches(PyExc_AttributeError))
      throw;
    throw InputError("F: " + what + ": " + printable(py::str(e.value()).cast<std::string>()));
  }
}

// The caller's F (a scipy.sparse matrix or array of any format, or a 2-D array of numbers) as canonical float32
// CSR (sorted, duplicates summed; a copy), after the checks above.
py::object checked_csr(const py::object& F, std::int64_t n) {
  const py::module_ np = py::module_::import("numpy");
  const py::module_ sparse = py::module_::import("scipy.sparse");
  const auto shape_text = [](const py::object& shape) { return py::str(shape).cast<std::string>(); };
  const std::string sizes = " but the scene has " + std::to_string(n) + " patches";
  py::object source;
  if (sparse.attr("issparse")(F).cast<bool>()) {
    const py::tuple shape = F.attr("shape");
    const py::object rows = shape.size() == 2 ? py::object(shape[0]) : py::none(),
                     cols = shape.size() == 2 ? py::object(shape[1]) : py::none();
    if (shape.size() != 2 || rows.not_equal(py::int_(n)) || cols.not_equal(py::int_(n)))
      throw InputError("F is " + shape_text(shape) + sizes);
    const std::string format = F.attr("format").cast<std::string>();
    if (format == "csr" || format == "csc") {
      check_compressed(F, n, n, format == "csr" ? "row" : "column");
      source = F;
    } else if (format == "bsr") {
      const auto block = F.attr("blocksize").cast<std::pair<std::int64_t, std::int64_t>>();
      if (block.first < 1 || block.second < 1 || n % block.first != 0 || n % block.second != 0)
        throw InputError("F's blocks (" + std::to_string(block.first) + " x " + std::to_string(block.second) +
                         ") do not tile " + std::to_string(n) + " x " + std::to_string(n));
      check_compressed(F, n / block.first, n / block.second, "block row", block.first * block.second);
      source = F;
    } else {
      // COO as it is; DIA, DOK and LIL through their own tocoo (no index of theirs is used to address memory).
      source = format == "coo" ? F : scipy_call("tocoo", [&] { return F.attr("tocoo")(); });
      check_coordinates(source, n);
    }
  } else {
    const py::object a = scipy_call("not a FormFactors, a scipy.sparse matrix or an array of numbers",
                                    [&] { return np.attr("asarray")(F); });
    if (a.attr("ndim").cast<int>() != 2 || a.attr("shape").cast<py::tuple>()[0].cast<std::int64_t>() != n ||
        a.attr("shape").cast<py::tuple>()[1].cast<std::int64_t>() != n)
      throw InputError("F is an array of shape " + shape_text(a.attr("shape")) + sizes +
                       " (F must be a FormFactors, a scipy.sparse matrix or an N x N array of numbers)");
    check_values(a, a.attr("size").cast<std::int64_t>());
    source = a;
  }
  const py::object csr = scipy_call("conversion to CSR", [&] {
    return sparse.attr("csr_matrix")(source, py::arg("dtype") = np.attr("float32"), py::arg("copy") = true);
  });
  // Canonical whatever flags the caller's matrix carried: sorted columns, duplicates summed.
  csr.attr("has_sorted_indices") = false;
  csr.attr("has_canonical_format") = false;
  csr.attr("sum_duplicates")();
  if (csr.attr("nnz").cast<std::int64_t>() > kMaxEntries) throw InputError("F has more than 2^31 - 1 entries");
  return csr;
}



// The CLI's per-patch form-factor fields (apps/pipeline.cpp form_factor_fields), in its order.
py::dict diagnostics(const FormFactorsResult& r) {
  const FormFactorDiagnostics d = diagnose_form_factors(r.ff.F, r.area, r.ff.rays, r.ff.back_hits);
  py::dict out;
  out["row_sum"] = copy_array(d.row_sum);
  out["reciprocity_error"] = copy_array(d.reciprocity_error);
  if (!r.ff.rays.empty()) {
    const auto counts = [](const std::vector<std::uint32_t>& c) {
      std::vector<std::int64_t> v(c.begin(), c.end());
      return copy_array(v);
    };
    out["rays"] = counts(r.ff.rays);
    out["escaped"] = counts(r.ff.escaped);
    out["back_hits"] = counts(r.ff.back_hits);
    out["row_std_error"] = copy_array(d.row_std_error);
  }
  if (!r.ff.row_std_error.empty())  // the analytic route: each row sum's standard error from its visibility
    out["row_std_error"] = py::array_t<double>(r.ff.row_std_error.size(), r.ff.row_std_error.data());
  return out;
}

FormFactorsResult form_factors(const Scene& scene, long rays, double rays_per_area, long min_rays,
                               std::uint64_t seed, bool reciprocity, bool stratified, long long threads,
                               bool analytic, long visibility_samples, double analytic_cutoff, bool sobol_rays,
                               const py::object& emitter_columns) {
  check_thread_count(threads, "threads");
  const long emitters = emitter_request(emitter_columns);
  FormFactorsResult r;
  r.area = scene.patches.area;
  if (!analytic && analytic_cutoff != 0)
    throw InputError("analytic_cutoff is an option of analytic=True (the ray route has no pairs to drop)");
  if (analytic && !(analytic_cutoff >= 0 && analytic_cutoff < 1))
    throw InputError("analytic_cutoff must be in [0, 1), got " + std::to_string(analytic_cutoff));
  if (analytic) {
    // The ray options mean nothing to the analytic route: refused when changed from their defaults.
    if (rays != 1000 || rays_per_area != 0 || min_rays != 16 || !stratified || !sobol_rays ||
        emitters != kAutoEmitterSamples)
      throw InputError("analytic=True computes F without cosine rays: rays, rays_per_area, min_rays, stratified, "
                       "sobol_rays and emitter_columns cannot be honoured (leave them at their defaults)");
    AnalyticFormFactorOptions a;
    a.seed = seed;
    a.max_visibility_samples = visibility_samples;
    a.cutoff = analytic_cutoff;
    r.ff = interruptible([&] {
      ThreadLimit limit(static_cast<int>(threads));
      Timer timer;
      const EmbreeVisibility visibility(scene.patches);
      r.timings["embree_scene"] = timer.seconds();
      timer.reset();
      AnalyticFormFactors result = analytic_form_factors(scene.patches, visibility, a);
      r.timings["form_factors"] = timer.seconds();
      r.info["analytic_pairs"] = double(result.pairs);
      r.info["analytic_clear_pairs"] = double(result.clear_pairs);
      r.info["analytic_hidden_pairs"] = double(result.hidden_pairs);
      r.info["analytic_sampled_pairs"] = double(result.sampled_pairs);
      r.info["analytic_visibility_rays"] = double(result.visibility_rays);
      r.info["analytic_rows_scaled"] = double(result.rows_scaled);
      r.info["analytic_dropped_pairs"] = double(result.dropped_pairs);
      double bound = 0;
      for (double b : result.cutoff_bound) bound = std::max(bound, b);
      r.info["analytic_largest_cutoff_bound"] = bound;
      return std::move(result.form_factors);
    });
    return r;
  }
  if (!stratified && sobol_rays)
    throw InputError("stratified=False (independent rays) needs sobol_rays=False: Sobol points are stratified");
  FormFactorOptions o;
  o.rays_per_patch = rays;
  o.rays_per_area = rays_per_area;
  o.min_rays = min_rays;
  o.seed = seed;
  o.stratified = stratified;
  o.sobol = sobol_rays;
  r.ff = estimate(scene, o, emitters, static_cast<int>(threads), r.timings);
  if (reciprocity) {
    const ReciprocityChange change = interruptible([&] { return enforce_reciprocity(r.ff.F, r.area); });
    r.info["reciprocity_max_relative_change"] = change.max_relative_change;
    r.info["reciprocity_mean_relative_change"] = change.mean_relative_change;
    r.info["reciprocity_rows_rescaled"] = static_cast<double>(change.rows_rescaled);
  }
  return r;
}

}  // namespace

SparseF form_factor_matrix(const py::object& F, const Scene& scene, long rays, std::uint64_t seed, int threads,
                           std::map<std::string, double>& timings, FormFactors* sampling) {
  const auto n = static_cast<Eigen::Index>(scene.patches.size());
  if (F.is_none()) {
    FormFactorOptions o;  // the recommended route, as the CLI's defaults
    o.rays_per_patch = rays;
    o.seed = seed;
    o.sobol = true;
    FormFactors ff = estimate(scene, o, kAutoEmitterSamples, threads, timings);
    SparseF f = std::move(ff.F);
    if (sampling) *sampling = std::move(ff);
    return f;
  }
  if (py::isinstance<FormFactorsResult>(F)) {
    const FormFactors& ff = F.cast<const FormFactorsResult&>().ff;
    const SparseF& f = ff.F;
    if (f.rows() != n)
      throw InputError("F is " + std::to_string(f.rows()) + " x " + std::to_string(f.cols()) + " but the scene has " +
                       std::to_string(n) + " patches");
    if (sampling) {
      *sampling = ff;
      sampling->F = SparseF();  // the record only: the caller has F
    }
    return f;
  }
  // A caller's matrix: checked, canonical float32 CSR with int32 indices (a copy), then its arrays into Eigen's
  // layout; the float32 values checked again (a float64 above 3.4e38, or a sum of duplicates, becomes inf).
  const py::object csr = checked_csr(F, n);
  const auto data = csr.attr("data").cast<CArray<float>>();
  const auto indices = csr.attr("indices").cast<CArray<std::int32_t>>();
  const auto indptr = csr.attr("indptr").cast<CArray<std::int32_t>>();
  const std::int32_t nnz = indptr.data()[n];
  for (Eigen::Index i = 0; i < n; ++i)
    for (std::int32_t k = indptr.data()[i]; k < indptr.data()[i + 1]; ++k)
      if (!(std::isfinite(data.data()[k]) && data.data()[k] >= 0))
        throw InputError("F(" + std::to_string(i) + ", " + std::to_string(indices.data()[k]) + ") = " +
                         number_text(data.data()[k]) + " as float32: form factors must be finite and >= 0");
  const Eigen::Map<const SparseF::Base> map(n, n, nnz, indptr.data(), indices.data(), data.data());
  return SparseF(map);
}

void bind_form_factors(py::module_& m) {
  py::class_<FormFactorsResult>(m, "FormFactors", R"doc(Form factors of a scene (radwalk.form_factors).

F: scipy.sparse.csr_matrix, N x N, F[i, j] = fraction of the power leaving patch i that reaches the front of j.
  Its data (float32), indices and indptr (int32) are read-only VIEWS of the library's CSR arrays (Eigen's
  row-major float matrix with 32-bit indices has scipy's CSR layout), no copy; each access makes a new
  csr_matrix over the same memory, which keeps this object alive. F.copy() gives a writable copy.
rays, escaped, back_hits: per-patch counts (uint32 views; empty when F was read from a file).
diagnostics: the per-patch form-factor fields of the CLI's CSV, in its order.
Pass the object itself (not .F) to solve, random_walk, compare, exact_variance: that skips the conversion.)doc")
      .def_property_readonly(
          "F", [](py::object self) { return csr_view(self.cast<const FormFactorsResult&>().ff.F, self); },
          "F as a scipy.sparse.csr_matrix (N, N) float32 (dimensionless fractions), over views "
          "of the library's arrays (no copy).")
      .def_property_readonly(
          "rays",
          [](py::object self) {
            const auto& ff = self.cast<const FormFactorsResult&>().ff;
            return view(ff.rays.data(), ff.rays.size(), 1, self);
          },
          "Rays traced from each patch n_i, (N,) uint32 view (empty, shape (0,), when F was read).")
      .def_property_readonly(
          "escaped",
          [](py::object self) {
            const auto& ff = self.cast<const FormFactorsResult&>().ff;
            return view(ff.escaped.data(), ff.escaped.size(), 1, self);
          },
          "Rays from each patch that hit nothing, (N,) uint32 view (empty when F was read).")
      .def_property_readonly(
          "back_hits",
          [](py::object self) {
            const auto& ff = self.cast<const FormFactorsResult&>().ff;
            return view(ff.back_hits.data(), ff.back_hits.size(), 1, self);
          },
          "Rays from each patch whose first hit was the back of a patch, (N,) uint32 view (empty when F was read).")
      .def_property_readonly(
          "nnz", [](const FormFactorsResult& r) { return r.ff.F.nonZeros(); },
          "The number of stored entries of F (int).")
      .def_readonly("timings", &FormFactorsResult::timings,
                    "Stage -> wall time (dict str -> float, s): embree_scene, form_factors.")
      .def_readonly(
          "info", &FormFactorsResult::info,
          "The reciprocity change when enforced (dict str -> float, the JSON's reciprocity_* keys); empty otherwise.")
      .def_property_readonly("diagnostics", &diagnostics,
                             "Per-patch diagnostics as a dict of (N,) numpy arrays, in the order of the CLI's CSV: "
                             "row_sum, reciprocity_error (float64, dimensionless), and when F was estimated rays, "
                             "escaped, back_hits (int64), row_std_error (float64) "
                             "(formfactor/form_factor_diagnostics.h). Computed on access.")
      .def(
          "__len__", [](const FormFactorsResult& r) { return r.ff.F.rows(); }, "The number of patches N (int).")
      .def("__repr__", [](const FormFactorsResult& r) {
        return "<radwalk.FormFactors " + std::to_string(r.ff.F.rows()) + " x " + std::to_string(r.ff.F.cols()) +
               ", " + std::to_string(r.ff.F.nonZeros()) + " non-zeros>";
      });

  m.def("form_factors", &form_factors, py::arg("scene"), py::arg("rays") = 1000, py::arg("rays_per_area") = 0.0,
        py::arg("min_rays") = 16, py::arg("seed") = 1, py::arg("reciprocity") = false, py::arg("stratified") = true,
        py::arg("threads") = 0, py::arg("analytic") = false, py::arg("visibility_samples") = 1024,
        py::arg("analytic_cutoff") = 0.0, py::arg("sobol_rays") = true, py::arg("emitter_columns") = "auto",
        R"doc(Estimates the form factors of the scene by cosine-weighted ray shooting (Embree): a FormFactors.

The FormFactors holds F, an (N, N) float32 scipy.sparse.csr_matrix of dimensionless fractions, and (N,) per-patch
ray counts.

The CLI's `radwalk formfactors` and the F of `solve`/`compare`, with the same options and the same result for the
same seed (bit-identical for any thread count):
  rays: rays per patch (--rays); rays_per_area > 0 (rays per mesh length unit squared):
  max(min_rays, round(rays_per_area * area)) instead
  (--rays-per-area, --min-rays); seed (--seed); reciprocity: average A_i F_ij and A_j F_ji (--reciprocity);
  sobol_rays: randomised Sobol cosine rays (--sobol-rays, the default; False: jittered strata, --no-sobol-rays);
  stratified=False with sobol_rays=False draws plain binomial counts (tests); emitter_columns: "auto" (the
  default: a third of the rays per patch as shadow samples of the emitter columns when the scene has at most that
  many emitter patches), 0 (none) or M (--emitter-columns); threads: 0 = all cores.
analytic=True: the CLI's --analytic (docs/form-factors.md, "The analytic route"): the exact form factor of every
  pair of patches that face each other times its visibility (1 or 0 where proven, else estimated by at most
  visibility_samples point pairs, a power of 2 >= 32); reciprocal; diagnostics["row_std_error"] per row, info
  the pair counts. analytic_cutoff > 0 (--analytic-cutoff) drops pairs whose F are both proven at most it (info
  analytic_dropped_pairs, analytic_largest_cutoff_bound). The ray options must stay at their defaults (refused
  otherwise).
F depends only on the geometry: edits of Scene.rho or Scene.E do not call for new form factors.
The GIL is released while rays are traced.)doc");
}

}  // namespace radwalk::python
