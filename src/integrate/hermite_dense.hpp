#pragma once
// Dense output for one-step methods from the step ends alone: the Hermite polynomial through
// (y, f) at the last k step ends t₋ₖ₊₁ < … < t₀, read on [t₋₁, t₀], of order 2k − 1 (of lower
// degree through fewer ends while the history is that short, e.g. after a restart). No
// right-hand-side evaluations beyond the steps' own; ARKODE's cubic interpolant is O(h⁴), too
// coarse for fifth- and sixth-order tables at tight tolerances, and its quartic and quintic ones
// evaluate f at every sample. ARKODE's tables use k = 4 (order 7) up to order 6 and k = 6
// (order 11) for the eighth-order table, whose long steps leave even that interpolant the
// larger part of the sampled error (docs/benchmarks.md, work–precision).

#include <cstddef>
#include <vector>

namespace lagrange::integration {

/// The last `nodes` step ends (t, y, f = y') and the interpolant through them.
class HermiteDense {
 public:
  /// Dense output of order 2·nodes − 1 for states of size n.
  HermiteDense(size_t n, size_t nodes) : n_(n), nodes_(nodes), t_(nodes), y_(nodes), f_(nodes) {}
  /// Forgets the history (the state was changed: a restart).
  void clear() { count_ = 0; }
  /// The time of the newest node, or −∞ without one.
  double newest() const;
  /// Appends the step end (t, y, f); t must exceed newest().
  void push(double t, const double* y, const double* f);
  /// y(t) for t in [second newest, newest] into out (needs two nodes).
  void evaluate(double t, double* out);

 private:
  void build();

  size_t n_;
  size_t nodes_;
  size_t count_ = 0;  // nodes held (at most nodes_), oldest first
  std::vector<double> t_;
  std::vector<std::vector<double>> y_, f_;
  bool built_ = false;
  std::vector<double> z_;                   // the repeated nodes of the Newton form
  std::vector<std::vector<double>> coeff_;  // Newton coefficients, one vector per degree
};

}  // namespace lagrange::integration
