#include "integrate/hermite_dense.hpp"

#include <cmath>
#include <stdexcept>

namespace lagrange::integration {

double HermiteDense::newest() const {
  return count_ == 0 ? -HUGE_VAL : t_[count_ - 1];
}

void HermiteDense::push(double t, const double* y, const double* f) {
  if (count_ == nodes_) {  // drop the oldest node
    for (size_t i = 0; i + 1 < nodes_; ++i) {
      t_[i] = t_[i + 1];
      y_[i].swap(y_[i + 1]);
      f_[i].swap(f_[i + 1]);
    }
    count_ = nodes_ - 1;
  }
  t_[count_] = t;
  y_[count_].assign(y, y + n_);
  f_[count_].assign(f, f + n_);
  ++count_;
  built_ = false;
}

// Newton form on the doubled nodes z = (t₀, t₀, t₁, t₁, …): divided differences where a repeated
// node takes the derivative, p(t) = Σₖ c_k Π_{m<k} (t − z_m).
void HermiteDense::build() {
  const size_t m = 2 * count_;
  z_.resize(m);
  std::vector<std::vector<double>> table(m, std::vector<double>(n_));
  for (size_t i = 0; i < m; ++i) {
    z_[i] = t_[i / 2];
    table[i] = y_[i / 2];
  }
  coeff_.assign(m, std::vector<double>(n_));
  coeff_[0] = table[0];
  for (size_t j = 1; j < m; ++j) {
    for (size_t i = m - 1; i >= j; --i) {  // column j in place, bottom up
      if (j == 1 && i % 2 == 1) {
        table[i] = f_[i / 2];
      } else {
        const double span = z_[i] - z_[i - j];
        for (size_t k = 0; k < n_; ++k) table[i][k] = (table[i][k] - table[i - 1][k]) / span;
      }
    }
    coeff_[j] = table[j];
  }
  built_ = true;
}

void HermiteDense::evaluate(double t, double* out) {
  if (count_ < 2) throw std::logic_error("HermiteDense: fewer than two nodes");
  if (!built_) build();
  const size_t m = z_.size();
  for (size_t k = 0; k < n_; ++k) out[k] = coeff_[m - 1][k];
  for (size_t j = m - 1; j-- > 0;) {  // Horner on the Newton form
    const double factor = t - z_[j];
    for (size_t k = 0; k < n_; ++k) out[k] = out[k] * factor + coeff_[j][k];
  }
}

}  // namespace lagrange::integration
