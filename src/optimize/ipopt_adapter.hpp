#pragma once
// Ipopt's TNLP over a Transcription: a thin class that copies arrays, and the solve around it.

#include <atomic>
#include <string>
#include <utility>
#include <vector>

#include "optimize/transcription.hpp"

namespace lagrange::collocation {

/// What Ipopt returned.
struct IpoptOutcome {
  bool optimal = false;
  std::string status;     ///< in words
  std::vector<double> x;  ///< the last iterate (the solution when optimal)
  /// Its multipliers: of the variables' lower and upper bounds, and of the constraints.
  std::vector<double> z_lower, z_upper, lambda;
  int iterations = 0;
  double function_seconds = 0.0;  ///< spent in the transcription's functions
  bool exact_hessian = false;     ///< Ipopt used the transcription's Hessian
  bool interrupted = false;       ///< stopped because `interrupt` was set
};

/// Solve the NLP with Ipopt (MUMPS, limited-memory Hessian) from the transcription's guess,
/// `options` applied after the defaults (a value is an integer, a number or a word by its form).
/// std::invalid_argument for an option Ipopt rejects. Ipopt stops after the iteration during
/// which `interrupt` (when given) is set. With `warm_start_init_point=yes`, the multipliers
/// start at `previous`'s (an earlier solve of an NLP of the same size: a homotopy's last stage).
IpoptOutcome solve_with_ipopt(Transcription& nlp,
                              const std::vector<std::pair<std::string, std::string>>& options,
                              bool verbose, const std::atomic<bool>* interrupt = nullptr,
                              const IpoptOutcome* previous = nullptr);

}  // namespace lagrange::collocation
