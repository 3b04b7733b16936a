#pragma once
// numpy arrays in and out of the binding: checked shapes with messages that say expected vs got,
// and read-only views over C++ memory kept alive by a Python owner.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>
#include <vector>

namespace lagrange::python {

/// A C-contiguous float64 array (converted when needed).
using DoubleArray =
    pybind11::array_t<double, pybind11::array::c_style | pybind11::array::forcecast>;

/// The `n` numbers of the 1-D array `a`; ValueError "q: expected 2 values, got an array of shape
/// (3,)" when it has another shape.
const double* vector_data(const DoubleArray& a, size_t n, const char* what);

/// Checks that `a` is rows × n (2-D); ValueError naming `what` and both shapes otherwise.
void require_matrix(const DoubleArray& a, size_t n, const char* what);

/// A read-only view of `rows` values starting at `data`, `stride` doubles apart, whose memory
/// `owner` keeps alive (the array's base).
pybind11::array column_view(const double* data, size_t rows, size_t stride, pybind11::handle owner);

/// A read-only rows × cols row-major view of `data`, kept alive by `owner`.
pybind11::array matrix_view(const double* data, size_t rows, size_t cols, pybind11::handle owner);

/// A new 1-D array holding a copy of `values`.
pybind11::array_t<double> to_array(const std::vector<double>& values);

}  // namespace lagrange::python
