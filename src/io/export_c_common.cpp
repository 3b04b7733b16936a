// Pieces shared by the C exporters: the Cholesky solve and name lists for header comments.

#include "io/export_c_common.hpp"

#include <fmt/format.h>

namespace lagrange {

const char* c_cholesky_source() {
  return R"C(
/* Cholesky factorisation in place (lower triangle of A, n×n row-major); 1 when not SPD. */
static int lg_chol(double* A, int n) {
  for (int j = 0; j < n; ++j) {
    double s = A[j * n + j];
    for (int k = 0; k < j; ++k) s -= A[j * n + k] * A[j * n + k];
    if (!(s > 0.0)) return 1;
    A[j * n + j] = sqrt(s);
    for (int i = j + 1; i < n; ++i) {
      double r = A[i * n + j];
      for (int k = 0; k < j; ++k) r -= A[i * n + k] * A[j * n + k];
      A[i * n + j] = r / A[j * n + j];
    }
  }
  return 0;
}

/* Solve L Lᵀ x = b in place. */
static void lg_chol_solve(const double* L, int n, double* b) {
  for (int i = 0; i < n; ++i) {
    double s = b[i];
    for (int k = 0; k < i; ++k) s -= L[i * n + k] * b[k];
    b[i] = s / L[i * n + i];
  }
  for (int i = n - 1; i >= 0; --i) {
    double s = b[i];
    for (int k = i + 1; k < n; ++k) s -= L[k * n + i] * b[k];
    b[i] = s / L[i * n + i];
  }
}
)C";
}

std::string c_name_list(const std::vector<std::string>& names) {
  std::string s;
  for (size_t i = 0; i < names.size(); ++i) s += fmt::format("{}{}", i ? ", " : "", names[i]);
  return s.empty() ? std::string("(none)") : s;
}

}  // namespace lagrange
