#include "arrays.hpp"

#include <string>

namespace py = pybind11;

namespace lagrange::python {

namespace {

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

py::array read_only(py::array a) {
  a.attr("flags").attr("writeable") = false;
  return a;
}

}  // namespace

const double* vector_data(const DoubleArray& a, size_t n, const char* what) {
  if (a.ndim() != 1 || static_cast<size_t>(a.shape(0)) != n)
    throw py::value_error(std::string(what) + ": expected " + std::to_string(n) +
                          " values, got an array of shape " + shape_text(a));
  return a.data();
}

void require_matrix(const DoubleArray& a, size_t n, const char* what) {
  if (a.ndim() != 2 || static_cast<size_t>(a.shape(1)) != n)
    throw py::value_error(std::string(what) + ": expected an array of shape (rows, " +
                          std::to_string(n) + "), got " + shape_text(a));
}

py::array column_view(const double* data, size_t rows, size_t stride, py::handle owner) {
  return read_only(py::array(py::dtype::of<double>(), {rows},
                             {static_cast<py::ssize_t>(stride * sizeof(double))}, data, owner));
}

py::array matrix_view(const double* data, size_t rows, size_t cols, py::handle owner) {
  return read_only(py::array(
      py::dtype::of<double>(), {rows, cols},
      {static_cast<py::ssize_t>(cols * sizeof(double)), static_cast<py::ssize_t>(sizeof(double))},
      data, owner));
}

py::array_t<double> to_array(const std::vector<double>& values) {
  return py::array_t<double>(static_cast<py::ssize_t>(values.size()), values.data());
}

}  // namespace lagrange::python
