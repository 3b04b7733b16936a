#pragma once
// DOP853 as a resumable object: integrate_dop853 walks the output grid with it, and the stepping
// interface (include/lagrange/stepper.hpp) keeps one between calls (docs/theory.md §8, DOP853).

#include <vector>

#include "integrate/dop853_coefficients.hpp"
#include "lagrange/integrator.hpp"

namespace lagrange::integration {

/// One DOP853 integration: the state y (owned by the caller), its stages and the last step's
/// interpolant. Steps never cross `end()`: the step that would reach it (within 1 %) lands on it.
class Dop853 {
 public:
  Dop853(const OdeProblem& problem, const IntegratorOptions& options, std::vector<double>& y,
         double t_end);

  /// Starts at (t, y): f(t, y), and with `keep_step` false a first step from Hairer's heuristic.
  void start(double t, bool keep_step);
  /// One accepted step from t toward end() (the last one lands on it); returns the time reached.
  /// A step shortened to land on end() keeps the step size it replaced for the step after it.
  double step();
  /// y(t) for t in the last step into out: the continuous extension (its three stages are
  /// evaluated on the first call of the step).
  void interpolate(double t, double* out);

  double time() const { return t_; }
  double end() const { return t_end_; }
  /// Moves the end the steps land on (at or after time()).
  void set_end(double t_end) { t_end_ = t_end; }
  IntegratorStats stats() const { return stats_; }
  /// Hairer's stiffness test (docs/theory.md §5.6, "Noticing stiffness during the run"): true
  /// once h·ρ, estimated after each accepted step from its last stages, has exceeded the
  /// stability boundary on kStiffSteps tests with no kSoftSteps passing ones in a row between.
  bool stiff() const { return stiff_tests_ >= kStiffSteps; }
  /// The time of the step that made the test conclude (stiff() true).
  double stiff_since() const { return stiff_since_; }

  static constexpr double kStabilityBoundary = 6.1;  ///< h·ρ at DOP853's (Hairer's value)
  static constexpr long kStiffSteps = 15;
  static constexpr long kSoftSteps = 6;

 private:
  void f(double t, const double* y, std::vector<double>& out);
  void stage_state(const std::vector<double>& a, double h);
  void stages(double h);
  double error(double h);
  double weight(size_t i, double size) const;
  void accept(double h, bool last, double h_next);
  void test_stiffness(double h);
  double initial_step();
  void build_dense();

  const OdeProblem& problem_;
  const IntegratorOptions& options_;
  const Dop853Coefficients& table_;
  size_t n_;
  double t_end_;
  std::vector<double>& y_;
  std::vector<std::vector<double>> k_;  // the 16 stage derivatives
  std::vector<double> y_old_, y_new_, stage_, scale_;
  std::vector<std::vector<double>> dense_;  // F₀ … F₆ of the last step
  double t_ = 0.0, t_old_ = 0.0, h_ = 0.0, h_old_ = 0.0;
  bool first_is_last_ = false;  // k_[12] holds f at y_, the next step's first stage
  bool dense_ready_ = false;
  long rejections_ = 0;
  double previous_error_ = 1e-4;
  long stiff_tests_ = 0, soft_tests_ = 0;
  double stiff_since_ = 0.0;
  IntegratorStats stats_;
};

}  // namespace lagrange::integration
