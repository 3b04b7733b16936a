#pragma once
// Dense output of seventh order for one-step methods from the step ends alone: the Hermite
// polynomial through (y, f) at the last four step ends t₋₃ < … < t₀, read on [t₋₁, t₀] (of lower
// degree through fewer ends while the history is that short, e.g. after a restart). No
// right-hand-side evaluations beyond the steps' own; ARKODE's cubic interpolant is O(h⁴), too
// coarse for fifth- and sixth-order tables at tight tolerances, and its quartic and quintic ones
// evaluate f at every sample.

#include <cstddef>
#include <vector>

namespace lagrange::integration {

/// The last four step ends (t, y, f = y') and the interpolant through them.
class HermiteDense {
 public:
  explicit HermiteDense(size_t n) : n_(n) {}
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
  static constexpr size_t kNodes = 4;
  size_t count_ = 0;  // nodes held (at most kNodes), oldest first
  double t_[kNodes] = {};
  std::vector<double> y_[kNodes], f_[kNodes];
  bool built_ = false;
  std::vector<double> z_;                   // the repeated nodes of the Newton form
  std::vector<std::vector<double>> coeff_;  // Newton coefficients, one vector per degree
};

}  // namespace lagrange::integration
