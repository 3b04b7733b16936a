#include "symbolic/gradient_cache.hpp"

#include <algorithm>
#include <map>

#include "symbolic/time_partials.hpp"

namespace lagrange::symbolic {

GradientCache::GradientCache(const Kinematics& kin) : kin_(kin) {
  for (size_t i = 0; i < kin.q.size(); ++i) coordinate_of_.emplace(kin.q[i], i);
}

SparseGradient GradientCache::compute(const GiNaC::ex& e) {
  if (GiNaC::is_a<GiNaC::add>(e)) {  // Σ of the terms' (memoised) gradients
    std::map<size_t, GiNaC::ex> sum;
    for (size_t k = 0; k < e.nops(); ++k)
      for (const auto& [i, d] : gradient(e.op(k))) {
        auto [it, inserted] = sum.try_emplace(i, d);
        if (!inserted) it->second += d;
      }
    SparseGradient g;
    for (auto& [i, d] : sum)
      if (!d.is_zero()) g.emplace_back(i, d);
    return g;
  }
  std::vector<size_t> found;
  for (GiNaC::const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
    if (GiNaC::is_a<GiNaC::symbol>(*it)) {
      auto c = coordinate_of_.find(*it);
      if (c != coordinate_of_.end()) found.push_back(c->second);
    }
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  SparseGradient g;
  for (size_t i : found) {
    GiNaC::ex d = e.diff(kin_.q[i]);
    if (!d.is_zero()) g.emplace_back(i, d);
  }
  return g;
}

const SparseGradient& GradientCache::gradient(const GiNaC::ex& e) {
  auto it = memo_.find(e);
  if (it != memo_.end()) return it->second;
  SparseGradient g = compute(e);
  return memo_.emplace(e, std::move(g)).first->second;
}

// Plain coordinates: column i is ∂x/∂qᵢ; free-body coordinates go through K = ∂q̇/∂v.
std::vector<Vec3> GradientCache::jacobian(const Vec3& x) {
  std::vector<Vec3> J(kin_.v.size(), Vec3{0, 0, 0});
  for (size_t k = 0; k < 3; ++k) {
    std::map<size_t, GiNaC::ex> body;  // q index → ∂x/∂q, free-body coordinates
    for (const auto& [i, d] : gradient(x[k])) {
      if (i < kin_.plain)
        J[i][k] = d;
      else
        body.emplace(i, d);
    }
    if (body.empty()) continue;
    for (size_t col = kin_.plain; col < kin_.v.size(); ++col)
      for (const auto& [j, kjk] : kin_.K[col]) {
        auto it = body.find(j);
        if (it != body.end()) J[col][k] += it->second * kjk;
      }
  }
  return J;
}

GiNaC::ex GradientCache::rate(const GiNaC::ex& e) {
  GiNaC::ex r = partial_t(kin_, e);
  for (const auto& [i, d] : gradient(e)) r += d * kin_.qdot[i];
  return r;
}

}  // namespace lagrange::symbolic
