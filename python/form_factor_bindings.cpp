// radwalk.form_factors and the FormFactors type: F as a scipy.sparse.csr_matrix viewing the library's CSR arrays.
#include "bindings.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/timer.h"
#include "formfactor/form_factor_diagnostics.h"
#include "formfactor/reciprocity.h"
#include "visibility/embree_visibility.h"

namespace radwalk::python {
namespace {

// A read-only 1-D numpy view of n values at data, owned by base.
template <class T>
py::array_t<T> view(const T* data, std::size_t n, py::handle base) {
  py::array_t<T> a({static_cast<py::ssize_t>(n)}, {static_cast<py::ssize_t>(sizeof(T))}, data, base);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

// F (compressed) as scipy.sparse.csr_matrix((data, indices, indptr)) with views of its three arrays.
py::object csr_view(const SparseF& F, py::handle base) {
  const auto n = static_cast<std::size_t>(F.rows());
  const auto nnz = static_cast<std::size_t>(F.nonZeros());
  const py::object data = view(F.valuePtr(), nnz, base), indices = view(F.innerIndexPtr(), nnz, base),
                   indptr = view(F.outerIndexPtr(), n + 1, base);
  return py::module_::import("scipy.sparse")
      .attr("csr_matrix")(py::make_tuple(data, indices, indptr), py::arg("shape") = py::make_tuple(n, F.cols()),
                          py::arg("copy") = false);
}

FormFactors estimate(const Scene& scene, const FormFactorOptions& options, int threads,
                     std::map<std::string, double>& timings) {
  py::gil_scoped_release release;
  ThreadLimit limit(threads);
  Timer timer;
  const EmbreeVisibility visibility(scene.patches);
  timings["embree_scene"] = timer.seconds();
  timer.reset();
  FormFactors ff = estimate_form_factors(scene.patches, visibility, options);
  timings["form_factors"] = timer.seconds();
  return ff;
}

// The CLI's per-patch form-factor fields (apps/pipeline.cpp form_factor_fields), in its order.
py::dict diagnostics(const FormFactorsResult& r) {
  const FormFactorDiagnostics d = diagnose_form_factors(r.ff.F, r.area, r.ff.rays, r.ff.back_hits);
  py::dict out;
  out["row_sum"] = py::array_t<double>(d.row_sum.size(), d.row_sum.data());
  out["reciprocity_error"] = py::array_t<double>(d.reciprocity_error.size(), d.reciprocity_error.data());
  if (!r.ff.rays.empty()) {
    const auto counts = [](const std::vector<std::uint32_t>& c) {
      std::vector<std::int64_t> v(c.begin(), c.end());
      return py::array_t<std::int64_t>(v.size(), v.data());
    };
    out["rays"] = counts(r.ff.rays);
    out["escaped"] = counts(r.ff.escaped);
    out["back_hits"] = counts(r.ff.back_hits);
    out["row_std_error"] = py::array_t<double>(d.row_std_error.size(), d.row_std_error.data());
  }
  return out;
}

FormFactorsResult form_factors(const Scene& scene, long rays, double rays_per_area, long min_rays,
                               std::uint64_t seed, bool reciprocity, bool stratified, int threads) {
  FormFactorsResult r;
  r.area = scene.patches.area;
  FormFactorOptions o;
  o.rays_per_patch = rays;
  o.rays_per_area = rays_per_area;
  o.min_rays = min_rays;
  o.seed = seed;
  o.stratified = stratified;
  r.ff = estimate(scene, o, threads, r.timings);
  if (reciprocity) {
    py::gil_scoped_release release;
    const ReciprocityChange change = enforce_reciprocity(r.ff.F, r.area);
    r.info["reciprocity_max_relative_change"] = change.max_relative_change;
    r.info["reciprocity_mean_relative_change"] = change.mean_relative_change;
    r.info["reciprocity_rows_rescaled"] = static_cast<double>(change.rows_rescaled);
  }
  return r;
}

}  // namespace

SparseF form_factor_matrix(const py::object& F, const Scene& scene, long rays, std::uint64_t seed, int threads,
                           std::map<std::string, double>& timings) {
  const auto n = static_cast<Eigen::Index>(scene.patches.size());
  if (F.is_none()) {
    FormFactorOptions o;
    o.rays_per_patch = rays;
    o.seed = seed;
    return estimate(scene, o, threads, timings).F;
  }
  if (py::isinstance<FormFactorsResult>(F)) {
    const SparseF& f = F.cast<const FormFactorsResult&>().ff.F;
    if (f.rows() != n)
      throw InputError("F is " + std::to_string(f.rows()) + " x " + std::to_string(f.cols()) + " but the scene has " +
                       std::to_string(n) + " patches");
    return f;
  }
  // A scipy.sparse matrix: canonical float32 CSR with int32 indices (a copy), then its arrays into Eigen's layout.
  const py::module_ np = py::module_::import("numpy");
  const py::object csr = py::module_::import("scipy.sparse")
                             .attr("csr_matrix")(F, py::arg("dtype") = np.attr("float32"), py::arg("copy") = true);
  csr.attr("sum_duplicates")();  // sorts the indices of every row as well
  const auto shape = csr.attr("shape").cast<std::pair<long, long>>();
  if (shape.first != n || shape.second != n)
    throw InputError("F is " + std::to_string(shape.first) + " x " + std::to_string(shape.second) +
                     " but the scene has " + std::to_string(n) + " patches");
  const auto data = csr.attr("data").cast<py::array_t<float, py::array::c_style | py::array::forcecast>>();
  const auto indices = csr.attr("indices").cast<py::array_t<std::int32_t, py::array::c_style | py::array::forcecast>>();
  const auto indptr = csr.attr("indptr").cast<py::array_t<std::int32_t, py::array::c_style | py::array::forcecast>>();
  const Eigen::Map<const SparseF::Base> map(n, n, static_cast<Eigen::Index>(data.size()), indptr.data(), indices.data(),
                                            data.data());
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
      .def_property_readonly("F", [](py::object self) { return csr_view(self.cast<const FormFactorsResult&>().ff.F, self); })
      .def_property_readonly("rays", [](py::object self) {
        const auto& ff = self.cast<const FormFactorsResult&>().ff;
        return view(ff.rays.data(), ff.rays.size(), self);
      }, "Rays traced from each patch (n_i).")
      .def_property_readonly("escaped", [](py::object self) {
        const auto& ff = self.cast<const FormFactorsResult&>().ff;
        return view(ff.escaped.data(), ff.escaped.size(), self);
      }, "Rays from each patch that hit nothing.")
      .def_property_readonly("back_hits", [](py::object self) {
        const auto& ff = self.cast<const FormFactorsResult&>().ff;
        return view(ff.back_hits.data(), ff.back_hits.size(), self);
      }, "Rays from each patch whose first hit was the back of a patch.")
      .def_property_readonly("nnz", [](const FormFactorsResult& r) { return r.ff.F.nonZeros(); })
      .def_readonly("timings", &FormFactorsResult::timings, "Stage -> seconds (embree_scene, form_factors).")
      .def_readonly("info", &FormFactorsResult::info,
                    "The reciprocity change when enforced (the JSON's reciprocity_* keys); empty otherwise.")
      .def_property_readonly("diagnostics", &diagnostics,
                             "Per-patch diagnostics as a dict of numpy arrays, in the order of the CLI's CSV: "
                             "row_sum, reciprocity_error, and when F was estimated rays, escaped, back_hits "
                             "(int64), row_std_error (formfactor/form_factor_diagnostics.h). Computed on access.")
      .def("__len__", [](const FormFactorsResult& r) { return r.ff.F.rows(); })
      .def("__repr__", [](const FormFactorsResult& r) {
        return "<radwalk.FormFactors " + std::to_string(r.ff.F.rows()) + " x " + std::to_string(r.ff.F.cols()) +
               ", " + std::to_string(r.ff.F.nonZeros()) + " non-zeros>";
      });

  m.def("form_factors", &form_factors, py::arg("scene"), py::arg("rays") = 1000, py::arg("rays_per_area") = 0.0,
        py::arg("min_rays") = 16, py::arg("seed") = 1, py::arg("reciprocity") = false, py::arg("stratified") = true,
        py::arg("threads") = 0,
        R"doc(Estimates the form factors of the scene by cosine-weighted ray shooting (Embree): a FormFactors.

The CLI's `radwalk formfactors` and the F of `solve`/`compare`, with the same options and the same result for the
same seed (bit-identical for any thread count):
  rays: rays per patch (--rays); rays_per_area > 0: max(min_rays, round(rays_per_area * area)) instead
  (--rays-per-area, --min-rays); seed (--seed); reciprocity: average A_i F_ij and A_j F_ji (--reciprocity);
  stratified=False draws plain binomial counts (tests); threads: 0 = all cores.
F depends only on the geometry: edits of Scene.rho or Scene.E do not call for new form factors.
The GIL is released while rays are traced.)doc");
}

}  // namespace radwalk::python
