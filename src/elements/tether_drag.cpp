#include "elements/tether.hpp"

namespace lagrange::elements {

namespace {

Vec3 combine(const GiNaC::ex& a, const Vec3& x, const GiNaC::ex& b, const Vec3& y) {
  return {a * x[0] + b * y[0], a * x[1] + b * y[1], a * x[2] + b * y[2]};
}

// F = −½ ρ d ℓₛ C_D ‖v‖ v for the apparent velocity v = ṙ − w(r) (seed 000, "Tether Forces"),
// ‖v‖ as √(v·v + ε²), ε = 10⁻⁹ m/s, so that the derivative is finite at v = 0
// (docs/theory.md §4.5, Drag at rest).
Vec3 drag_force(const Tether& t, const GiNaC::ex& seg, const Vec3& v) {
  const GiNaC::numeric eps(1, 1000000000);
  const GiNaC::ex speed = GiNaC::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + eps * eps);
  const GiNaC::ex k = -t.air_density * t.diameter * seg * t.cd * speed / 2;
  return {k * v[0], k * v[1], k * v[2]};
}

}  // namespace

// docs/theory.md §4.5. Simple: the apparent velocity at the segment's midpoint, the force split
// half and half. Fine: v(σ) = σṙⱼ₋₁ + (1 − σ)ṙⱼ − w(σrⱼ₋₁ + (1 − σ)rⱼ) and the node shares
// ∫σF dσ, ∫(1 − σ)F dσ, by three-point Gauss–Legendre quadrature on [0, 1].
std::vector<Vec3> tether_drag(const Model& m, const Tether& t, const Wind* wind) {
  const size_t n = t.segments;
  std::vector<Vec3> force(n + 1, Vec3{0, 0, 0});
  if (t.drag == Tether::Drag::None) return force;
  const GiNaC::ex seg = t.length / GiNaC::numeric(static_cast<int>(n));
  std::vector<Vec3> r(n + 1), rdot(n + 1);
  for (size_t j = 0; j <= n; ++j) {
    r[j] = m.find_point(t.nodes[j])->pos;
    for (size_t k = 0; k < 3; ++k) rdot[j][k] = m.time_derivative(r[j][k]);
  }
  auto apparent = [&](size_t j, const GiNaC::ex& sigma) {
    const GiNaC::ex rest = 1 - sigma;
    Vec3 v = combine(sigma, rdot[j - 1], rest, rdot[j]);
    if (wind != nullptr) {
      const Vec3 w = wind->at(combine(sigma, r[j - 1], rest, r[j]));
      for (size_t k = 0; k < 3; ++k) v[k] -= w[k];
    }
    return v;
  };
  for (size_t j = 1; j <= n; ++j) {
    if (t.drag == Tether::Drag::Simple) {
      const Vec3 f = drag_force(t, seg, apparent(j, GiNaC::numeric(1, 2)));
      for (size_t k = 0; k < 3; ++k) {
        force[j - 1][k] += f[k] / 2;
        force[j][k] += f[k] / 2;
      }
      continue;
    }
    // Exact nodes ½ ∓ √15/10, so that the expressions (and the tape) hold no rounded numbers.
    const GiNaC::ex c = GiNaC::pow(GiNaC::ex(15), GiNaC::numeric(1, 2)) / 10;
    const std::array<GiNaC::ex, 3> sigma{GiNaC::numeric(1, 2) - c, GiNaC::numeric(1, 2),
                                         GiNaC::numeric(1, 2) + c};
    const std::array<GiNaC::ex, 3> weight{GiNaC::numeric(5, 18), GiNaC::numeric(8, 18),
                                          GiNaC::numeric(5, 18)};
    for (size_t i = 0; i < 3; ++i) {
      const Vec3 f = drag_force(t, seg, apparent(j, sigma[i]));
      for (size_t k = 0; k < 3; ++k) {
        force[j - 1][k] += weight[i] * sigma[i] * f[k];
        force[j][k] += weight[i] * (1 - sigma[i]) * f[k];
      }
    }
  }
  return force;
}

}  // namespace lagrange::elements
