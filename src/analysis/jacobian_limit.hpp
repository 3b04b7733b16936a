#pragma once
// The derivatives at a removable 0/0 of the differentiated tape (|v|·v, norm(v)·v at v = 0) as
// their limits, and NotDifferentiable where there is none (docs/theory.md §5.1, "Limits").

#include <functional>
#include <vector>

#include "lagrange/analysis.hpp"

namespace lagrange::analysis_detail {

/// Matrices of derivatives at a state y (n values), in a fixed order.
using DerivativesAt = std::function<std::vector<Eigen::MatrixXd>(const double* y)>;

/// `out`, evaluated at y, with each non-finite entry replaced by its limit: Richardson-
/// extrapolated from `at` along three directions (d, −d, d'). Throws NotDifferentiable (at time
/// t) when the limits differ by direction or are not finite.
void fill_limits(const std::vector<Eigen::MatrixXd*>& out, const DerivativesAt& at, const double* y,
                 size_t n, double t);

/// The derivative blocks of J that fill_limits completes, in one fixed order.
std::vector<Eigen::MatrixXd*> derivative_blocks(StateJacobian& J);

}  // namespace lagrange::analysis_detail
