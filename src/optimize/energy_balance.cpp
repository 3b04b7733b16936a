#include "optimize/energy_balance.hpp"

#include <algorithm>
#include <cmath>

#include "lagrange/tape.hpp"

namespace lagrange::collocation {

// docs/theory.md §10, "Checks": along the equations of motion dH/dt = Σ_s P_s, so
// H(T) − H(0) = Σ_s ∫ P_s dt up to the collocation's error.
EnergyBalance energy_balance(const Equations& eq, Transcription& nlp, const double* x) {
  EnergyBalance b;
  b.unsuitable = energy_balance_unsuitable(eq);
  if (!b.unsuitable.empty()) return b;
  const std::vector<PowerSource> sources = power_sources(eq);
  std::vector<GiNaC::ex> functions{energy_function(eq), eq.T};
  for (const PowerSource& s : sources) functions.push_back(s.power);
  const Tape tape = Tape::compile(functions, eq.tape_inputs());
  std::vector<double> out(functions.size()), work(std::max<size_t>(tape.work_size(), 1));
  const auto eval = [&](int k, int j) {
    const std::vector<double>& in =
        nlp.load(nlp.time(x, k, j), nlp.state(x, k, j), nlp.control(x, k, j));
    tape.eval(in.data(), out.data(), work.data());
  };
  const int N = nlp.intervals(), d = nlp.scheme().degree;
  const double h = nlp.horizon(x) / N;
  eval(0, 0);
  const double start = out[0];
  double flow = 0.0, kinetic = out[1];
  for (const PowerSource& s : sources) b.work.emplace_back(s.name, 0.0);
  for (int k = 0; k < N; ++k)
    for (int j = 1; j <= d; ++j) {
      eval(k, j);
      const double w = h * nlp.scheme().b[static_cast<size_t>(j - 1)];
      for (size_t s = 0; s < sources.size(); ++s) {
        b.work[s].second += w * out[2 + s];
        flow += w * std::fabs(out[2 + s]);
      }
      kinetic = std::max(kinetic, out[1]);
    }
  b.change = out[0] - start;  // the last evaluation is t = T
  b.scale = std::max(flow, kinetic);
  b.residual = b.change;
  for (const auto& w : b.work) b.residual -= w.second;
  return b;
}

}  // namespace lagrange::collocation
