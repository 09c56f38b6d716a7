#include "arrays.h"

#include "core/error.h"

namespace radwalk::python {

py::array_t<double> rgb_view(const PatchRgb& values, py::handle base) {
  return view(values.size() ? values.data() : static_cast<const double*>(nullptr),
              static_cast<std::size_t>(values.rows()), 3, base);
}

py::array_t<double> rgb_copy(const PatchRgb& values) {
  py::array_t<double> out({static_cast<py::ssize_t>(values.rows()), py::ssize_t{3}});
  auto a = out.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < values.rows(); ++i)
    for (Eigen::Index c = 0; c < 3; ++c) a(i, c) = values(i, c);
  return out;
}

py::array real_array(const py::object& value, const std::string& not_numbers, const std::string& not_real) {
  const py::module_ np = py::module_::import("numpy");
  py::object a;
  try {
    a = np.attr("asarray")(value);
  } catch (const py::error_already_set& e) {
    if (!e.matches(PyExc_ValueError) && !e.matches(PyExc_TypeError)) throw;
    throw InputError(not_numbers);
  }
  const std::string kind = a.attr("dtype").attr("kind").cast<std::string>();
  if (kind != "b" && kind != "i" && kind != "u" && kind != "f")
    throw InputError(not_real + " " + py::str(a.attr("dtype")).cast<std::string>());
  return a.cast<py::array>();
}

DoubleArray double_array(const py::object& value, const std::string& not_numbers, const std::string& not_real) {
  return real_array(value, not_numbers, not_real).cast<DoubleArray>();
}

std::string shape_text(const py::array& a) {
  std::string shape = "(";
  for (py::ssize_t k = 0; k < a.ndim(); ++k) shape += (k ? ", " : "") + std::to_string(a.shape(k));
  return shape + (a.ndim() == 1 ? ",)" : ")");
}

}  // namespace radwalk::python
