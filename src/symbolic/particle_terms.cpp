#include <map>

#include "lagrange/error.hpp"
#include "model/vec3_algebra.hpp"
#include "symbolic/gradient_cache.hpp"
#include "symbolic/mechanical_terms.hpp"
#include "symbolic/time_partials.hpp"

namespace lagrange::symbolic {

namespace {

using ExMap = std::map<GiNaC::ex, GiNaC::ex, GiNaC::ex_is_less>;
using ExVecMap = std::map<GiNaC::ex, Vec3, GiNaC::ex_is_less>;

GiNaC::ex key_of(const Vec3& col) {
  return GiNaC::lst{col[0], col[1], col[2]};
}

Vec3 vec_of(const GiNaC::ex& key, size_t offset = 0) {
  return {key.op(offset), key.op(offset + 1), key.op(offset + 2)};
}

}  // namespace

// docs/theory.md §8: M = Σₖ mₖ JₖᵀJₖ and h = Σₖ mₖ Jₖᵀ(g − bₖ). Columns of different particles
// that are the same expression (a chain point is its parent plus one link, so ∂x/∂θᵢ is
// shared by every point below link i) are grouped: Mᵢⱼ = Σ_(cols) (Σ m)·(colᵢ·colⱼ) and
// hᵢ = Σ_(col) col·(Σ m (g − b)), which keeps the expression size O(N²) for chains.
void add_particle_terms(const Kinematics& kin, MechanicalTerms& terms) {
  const Model& model = *kin.model;
  const size_t n = kin.v.size();
  const Vec3 g = model.gravity.value_or(Vec3{0, 0, 0});
  std::vector<ExMap> mass_of_pair(n * n);  // (i ≤ j) → (colᵢ, colⱼ) → Σ m
  std::vector<ExVecMap> force_of_col(n);   // i → colᵢ → Σ m (g − b)
  GradientCache cache(kin);
  for (const auto& particle : model.particles) {
    const Point* point = model.find_point(particle.point);
    if (point == nullptr) throw ModelError(particle.loc, "unknown point '" + particle.point + "'");
    if (depends_on_state(kin, particle.mass))
      throw ModelError(particle.loc, "the mass of the particle at '" + particle.point +
                                         "' depends on the state; expected a constant mass");
    const GiNaC::ex& m = particle.mass;
    const std::vector<Vec3> J = cache.jacobian(point->pos);
    Vec3 xdot, g_minus_b;
    for (size_t k = 0; k < 3; ++k) xdot[k] = cache.rate(point->pos[k]);
    const Vec3 g_k = particle.gravity ? g : Vec3{0, 0, 0};
    for (size_t k = 0; k < 3; ++k) g_minus_b[k] = g_k[k] - cache.rate(xdot[k]);
    terms.T += m / 2 * dot(xdot, xdot);
    terms.U -= m * dot(g_k, point->pos);
    std::vector<size_t> active;
    for (size_t i = 0; i < n; ++i)
      if (!model::is_zero(J[i])) active.push_back(i);
    for (size_t a = 0; a < active.size(); ++a) {
      const size_t i = active[a];
      GiNaC::ex key_i = key_of(J[i]);
      Vec3& f = force_of_col[i].try_emplace(key_i, Vec3{0, 0, 0}).first->second;
      for (size_t k = 0; k < 3; ++k) f[k] += m * g_minus_b[k];
      for (size_t b = a; b < active.size(); ++b) {
        const size_t j = active[b];
        GiNaC::ex key = GiNaC::lst{J[i][0], J[i][1], J[i][2], J[j][0], J[j][1], J[j][2]};
        auto [it, inserted] = mass_of_pair[i * n + j].try_emplace(key, m);
        if (!inserted) it->second += m;
      }
    }
  }
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = i; j < n; ++j) {
      GiNaC::ex mij = 0;
      for (const auto& [key, msum] : mass_of_pair[i * n + j])
        mij += msum * dot(vec_of(key, 0), vec_of(key, 3));
      terms.M(i, j) += mij;
      if (j != i) terms.M(j, i) += mij;
    }
    for (const auto& [key, f] : force_of_col[i]) terms.h[i] += dot(vec_of(key), f);
  }
}

}  // namespace lagrange::symbolic
