#pragma once
// Pieces shared by the C exporters (export_c.cpp, export_c_manipulator.cpp).

#include <string>
#include <vector>

namespace lagrange {

/// C99 source of `static int lg_chol(double* A, int n)` (Cholesky in place, lower triangle of a
/// row-major n×n matrix; 1 when not positive definite) and `static void lg_chol_solve(const
/// double* L, int n, double* b)` (solves L Lᵀ x = b in place).
const char* c_cholesky_source();

/// "a, b, c", or "(none)", for the comments of generated headers.
std::string c_name_list(const std::vector<std::string>& names);

}  // namespace lagrange
