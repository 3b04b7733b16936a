#pragma once
// The energy balance of a motion (docs/theory.md §10, "Checks"): the change of the energy
// function against the work of each non-conservative source, as optimize() prints it.

#include <ginac/ginac.h>

#include <string>
#include <utility>
#include <vector>

#include "lagrange/equations.hpp"

namespace lagrange {

/// One source of work on the model: a point force, a torque, a damper or a generalised force,
/// with its power Q_s·v in the state (t, q, v, u, p).
struct PowerSource {
  std::string name;  ///< "force at 'plane.cg' (line 93)", "generalised force on 'l'", …
  GiNaC::ex power;
};

/// The model's sources of work in model order (forces, torques, dampers, generalised forces);
/// sources with the same name are summed. Their powers add up to Q·v (docs/theory.md §10).
std::vector<PowerSource> power_sources(const Equations& eq);

/// The energy function H = Σ vᵢ ∂L/∂vᵢ − L (T + U when T is quadratic in v and U free of v).
GiNaC::ex energy_function(const Equations& eq);

/// Why dH/dt = Σ_s P_s does not hold for `eq`, or "" when it does: the energies or the
/// constraints depend on t or on an input, so that the motion's driver does work too.
std::string energy_balance_unsuitable(const Equations& eq);

/// H(T) − H(0) against each source's work over [0, T], by the collocation's quadrature.
struct EnergyBalance {
  std::string unsuitable;  ///< why no balance was computed ("" when it was)
  double change = 0.0;     ///< H(T) − H(0)
  std::vector<std::pair<std::string, double>> work;  ///< per source ∫ P_s dt, model order
  double residual = 0.0;  ///< change − Σ work: the collocation's error in the balance
  /// The energy the motion moves: the larger of Σ_s ∫ |P_s| dt (the sources' either way) and
  /// the largest kinetic energy (what a conservative motion trades with its potential).
  double scale = 0.0;
  /// |residual| / max(|change|, scale) (0 when both are 0).
  double relative_residual() const;
};

}  // namespace lagrange
