#pragma once
// The energy balance of a collocated solution (docs/theory.md §10, "Checks").

#include "lagrange/energy_balance.hpp"
#include "optimize/transcription.hpp"

namespace lagrange::collocation {

/// H(T) − H(0) from the collocated states and each source's work Σ_k h Σ_j b_j P_s(t_kj) by the
/// Radau quadrature, at the NLP point x; `unsuitable` set instead when the balance does not
/// hold for the model.
EnergyBalance energy_balance(const Equations& eq, Transcription& nlp, const double* x);

}  // namespace lagrange::collocation
