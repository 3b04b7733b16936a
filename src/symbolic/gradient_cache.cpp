#include "symbolic/gradient_cache.hpp"

#include <algorithm>
#include <map>

#include "symbolic/time_partials.hpp"

namespace lagrange::symbolic {

GradientCache::GradientCache(const Model& model) : model_(model) {
  for (size_t i = 0; i < model.coordinates.size(); ++i)
    coordinate_of_.emplace(model.coordinates[i].q, i);
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
    GiNaC::ex d = e.diff(model_.coordinates[i].q);
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

std::vector<Vec3> GradientCache::jacobian(const Vec3& x) {
  std::vector<Vec3> J(model_.coordinates.size(), Vec3{0, 0, 0});
  for (size_t k = 0; k < 3; ++k)
    for (const auto& [i, d] : gradient(x[k])) J[i][k] = d;
  return J;
}

GiNaC::ex GradientCache::rate(const GiNaC::ex& e) {
  GiNaC::ex r = partial_t(model_, e);
  for (const auto& [i, d] : gradient(e)) r += d * model_.coordinates[i].v;
  return r;
}

}  // namespace lagrange::symbolic
