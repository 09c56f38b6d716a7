#pragma once
// Conversions between numpy arrays and the C++ arrays, for every binding (bindings.h):
//   - views: numpy arrays over memory a C++ object owns (no copy), kept alive by that object, read-only unless the
//     binding lets Python write in place (Scene.rho, Scene.E);
//   - arguments: what a caller passes as an array (a numpy array, a list, a number), converted with numpy.asarray
//     and refused in one line (InputError) when numpy cannot make an array of it or its dtype is not real
//     (complex, object, strings); bool, integer and floating dtypes are read as float64.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstddef>
#include <string>
#include <vector>

#include "core/types.h"

namespace radwalk::python {

namespace py = pybind11;

// A float64 array in C order (rows contiguous), what the bindings read numbers from.
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

// A numpy view of `rows` rows of `columns` values of type T starting at data, owned by `base` (which the view keeps
// alive); shape (rows,) for one column, else (rows, columns); consecutive rows `row_stride` bytes apart (0: packed,
// columns * sizeof(T)); read-only unless `writable`.
template <class T>
py::array_t<T> view(const T* data, std::size_t rows, std::size_t columns, py::handle base, bool writable = false,
                    std::size_t row_stride = 0) {
  if (row_stride == 0) row_stride = columns * sizeof(T);
  std::vector<py::ssize_t> shape = {static_cast<py::ssize_t>(rows)}, strides = {static_cast<py::ssize_t>(row_stride)};
  if (columns > 1) {
    shape.push_back(static_cast<py::ssize_t>(columns));
    strides.push_back(static_cast<py::ssize_t>(sizeof(T)));
  }
  py::array_t<T> a(shape, strides, data, base);
  if (!writable) py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

// A read-only (N, 3) float64 view of a PatchRgb owned by `base` (shape (0, 3) when empty).
py::array_t<double> rgb_view(const PatchRgb& values, py::handle base);

// An owning (N, 3) float64 copy of a PatchRgb (for values computed on request, e.g. Result.B_err).
py::array_t<double> rgb_copy(const PatchRgb& values);

// An owning copy of `values` as a 1-D numpy array (shape (n,), dtype of T).
template <class T>
py::array_t<T> copy_array(const std::vector<T>& values) {
  return py::array_t<T>(static_cast<py::ssize_t>(values.size()), values.data());
}

// numpy.asarray(value) with a real dtype (kind b, i, u or f). InputError `not_numbers` when numpy cannot convert
// it; InputError "<not_real> DTYPE" when its dtype is not real (e.g. not_real = "F's values must be real numbers,
// not").
py::array real_array(const py::object& value, const std::string& not_numbers, const std::string& not_real);

// real_array as float64 in C order.
DoubleArray double_array(const py::object& value, const std::string& not_numbers, const std::string& not_real);

// "(3,)", "(2, 3)": an array's shape as numpy prints it.
std::string shape_text(const py::array& a);

}  // namespace radwalk::python
