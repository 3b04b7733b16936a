#pragma once
// Value references of an exported FMU (docs/fmu.md, "Variables"): one layout shared by
// modelDescription.xml and the generated C (lagrange_fmu_model.h), so the two cannot disagree.

#include <cstddef>
#include <string>
#include <vector>

#include "lagrange/compiled_model.hpp"

namespace lagrange::fmu {

/// Consecutive blocks: q, v, q̇, a, parameters, inputs, multipliers λ, observables (kinetic,
/// potential, energy, the model's outputs), then the FMU's own Baumgarte α, rtol and atol.
struct Layout {
  size_t q = 0, v, dq, a, p, u, lambda, obs, alpha, rtol, atol;
  size_t observables;  ///< 3 + the model's outputs
  explicit Layout(const CompiledModel& cm)
      : v(cm.nq),
        dq(v + cm.nv),
        a(dq + cm.nq),
        p(a + cm.nv),
        u(p + cm.np),
        lambda(u + cm.k),
        obs(lambda + cm.m),
        alpha(obs + 3 + cm.output_names.size()),
        rtol(alpha + 1),
        atol(rtol + 1),
        observables(3 + cm.output_names.size()) {}
};

/// What an FMU's generated C and description are made from besides the compiled model.
struct Description {
  std::string guid, identifier, model_name;
  bool model_exchange = true, co_simulation = true;
  double alpha = 20.0, rtol = 1e-8, atol = 1e-10;
  bool project = true;
  double t_end = 10.0, output_step = 0.01;
  std::vector<double> input_starts;  ///< k: each input's value at t = 0 (defaults of parameters)
};

/// lagrange_fmu_model.h: sizes, start values, value references and the observables tape.
std::string model_header(const CompiledModel& cm, const Description& d);

/// modelDescription.xml (FMI 2.0).
std::string model_description(const CompiledModel& cm, const Description& d);

}  // namespace lagrange::fmu
