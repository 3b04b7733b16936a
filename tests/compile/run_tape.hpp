#pragma once
// Evaluating a tape in tests.

#include <vector>

#include "lagrange/tape.hpp"

namespace lagrange {

/// The outputs of tape t at inputs x.
inline std::vector<double> run(const Tape& t, const std::vector<double>& x) {
  std::vector<double> out(t.num_outputs()), work(t.work_size());
  t.eval(x.data(), out.data(), work.data());
  return out;
}

}  // namespace lagrange
