#include "dynamics/tangent_jacobian.hpp"

#include <algorithm>
#include <map>

namespace lagrange::dynamics {

namespace {

// (R [e_k]×)_ic = Σ_l R_il E_lc with E = [e_k]×: E(b, a) = 1, E(a, b) = −1 for a = k + 1,
// b = k + 2 (mod 3), so only the columns c = a (R_ib) and c = b (−R_ia) are non-zero.
double tangent(const double* R, int k, int i, int c) {
  const int a = (k + 1) % 3, b = (k + 2) % 3;
  if (c == a) return R[3 * i + b];
  if (c == b) return -R[3 * i + a];
  return 0.0;
}

}  // namespace

TangentJacobian::TangentJacobian(const Pattern& Cq, size_t nq, const std::vector<size_t>& rotations)
    : rotations_(rotations) {
  std::vector<long> body(nq, -1);  // free body whose R holds coordinate j
  for (size_t b = 0; b < rotations.size(); ++b)
    for (size_t e = 0; e < 9; ++e) body[rotations[b] + e] = static_cast<long>(b);
  std::vector<size_t> column(nq);
  for (size_t j = 0; j < nq; ++j)
    if (body[j] < 0) {
      column[j] = plain_.size();
      plain_.push_back(static_cast<uint32_t>(j));
    }
  columns_ = plain_.size() + 3 * rotations.size();
  std::map<std::pair<size_t, size_t>, uint32_t> index;
  auto value_of = [&](size_t r, size_t c) {
    const auto [it, fresh] = index.emplace(std::make_pair(r, c), pattern_.size());
    if (fresh) pattern_.emplace_back(r, c);
    return it->second;
  };
  for (size_t e = 0; e < Cq.size(); ++e) {
    const auto [r, j] = Cq[e];
    if (body[j] < 0) {
      copies_.push_back({value_of(r, column[j]), static_cast<uint32_t>(e)});
      continue;
    }
    const size_t b = static_cast<size_t>(body[j]), o = rotations[b];
    const int i = static_cast<int>(j - o) / 3, c = static_cast<int>(j - o) % 3;
    for (int k = 0; k < 3; ++k) {
      const int a = (k + 1) % 3, d = (k + 2) % 3;
      if (c != a && c != d) continue;
      const uint32_t v = value_of(r, plain_.size() + 3 * b + static_cast<size_t>(k));
      terms_.push_back({v, static_cast<uint32_t>(e),
                        static_cast<uint32_t>(o + 3 * static_cast<size_t>(i) +
                                              static_cast<size_t>(c == a ? d : a)),
                        c == a ? 1.0 : -1.0});
    }
  }
  std::stable_sort(terms_.begin(), terms_.end(),
                   [](const Term& x, const Term& y) { return x.value < y.value; });
}

void TangentJacobian::reduce(const double* cq, const double* q, double* values) const {
  for (const Copy& c : copies_) values[c.value] = cq[c.cq];
  for (const Term& t : terms_) values[t.value] = 0.0;
  for (const Term& t : terms_) values[t.value] += t.sign * q[t.r] * cq[t.cq];
}

void TangentJacobian::expand(const double* x, const double* q, double* step) const {
  for (size_t c = 0; c < plain_.size(); ++c) step[plain_[c]] = x[c];
  for (size_t b = 0; b < rotations_.size(); ++b) {
    const double* R = q + rotations_[b];
    const double* theta = x + plain_.size() + 3 * b;
    for (int i = 0; i < 3; ++i)
      for (int c = 0; c < 3; ++c) {
        double s = 0.0;
        for (int k = 0; k < 3; ++k) s += theta[k] * tangent(R, k, i, c);
        step[rotations_[b] + static_cast<size_t>(3 * i + c)] = s;
      }
  }
}

}  // namespace lagrange::dynamics
