#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "lagrange/dynamics.hpp"
#include "lagrange/error.hpp"

namespace lagrange {

namespace {

// Smallest squared pivot of a Cholesky factor relative to the largest diagonal entry of the
// factored matrix: a conditioning test that costs O(n).
bool ill_conditioned(const Eigen::LLT<Eigen::MatrixXd>& llt, const Eigen::MatrixXd& A) {
  if (llt.info() != Eigen::Success) return true;
  const double scale = A.diagonal().cwiseAbs().maxCoeff();
  const double pivot = llt.matrixLLT().diagonal().cwiseAbs().minCoeff();
  return !(pivot * pivot > 1e-13 * scale);
}

std::string format_values(const std::vector<std::string>& names, const double* x,
                          const char* suffix) {
  std::string s;
  const size_t shown = std::min<size_t>(names.size(), 12);
  for (size_t i = 0; i < shown; ++i)
    s += fmt::format("{}{}{} = {:.6g}", i ? ", " : "", names[i], suffix, x[i]);
  if (shown < names.size()) s += fmt::format(", … ({} more)", names.size() - shown);
  return s;
}

}  // namespace

Dynamics::Dynamics(std::shared_ptr<const CompiledModel> model, std::vector<double> parameters)
    : model_(std::move(model)) {
  const CompiledModel& cm = *model_;
  in_.assign(cm.input_count(), 0.0);
  out_.assign(cm.dynamics.num_outputs(), 0.0);
  obs_out_.assign(cm.observables.num_outputs(), 0.0);
  sig_out_.assign(cm.inputs.num_outputs(), 0.0);
  M_.setZero(cm.n, cm.n);
  G_.setZero(cm.m, cm.n);
  Y_.setZero(cm.n, cm.m);
  S_.setZero(cm.m, cm.m);
  rhs_.setZero(cm.n);
  a_.setZero(cm.n);
  gamma_.setZero(cm.m);
  lambda_.setZero(cm.m);
  llt_M_ = Eigen::LLT<Eigen::MatrixXd>(cm.n);
  llt_S_ = Eigen::LLT<Eigen::MatrixXd>(cm.m);
  set_parameters(parameters);
}

void Dynamics::set_parameters(const std::vector<double>& values) {
  const CompiledModel& cm = *model_;
  if (values.size() != cm.np)
    throw std::invalid_argument(
        fmt::format("expected {} parameter values, got {}", cm.np, values.size()));
  params_ = values;
  std::copy(params_.begin(), params_.end(), in_.begin() + static_cast<long>(cm.p_offset()));
  // DESIGN.md §8: specialise the tapes to the parameter values by constant folding.
  dyn_ = cm.dynamics.specialize(cm.p_offset(), params_);
  obs_ = cm.observables.specialize(cm.p_offset(), params_);
  sig_ = cm.inputs.specialize(cm.p_offset(), params_);
  work_.assign(std::max({dyn_.work_size(), obs_.work_size(), sig_.work_size(), size_t{1}}), 0.0);
}

void Dynamics::load_inputs(double t, const double* q, const double* v) {
  const CompiledModel& cm = *model_;
  in_[0] = t;
  std::copy(q, q + cm.n, in_.begin() + static_cast<long>(cm.q_offset()));
  std::copy(v, v + cm.n, in_.begin() + static_cast<long>(cm.v_offset()));
  if (cm.k > 0) {
    sig_.eval(in_.data(), sig_out_.data(), work_.data());
    std::copy(sig_out_.begin(), sig_out_.end(), in_.begin() + static_cast<long>(cm.u_offset()));
  }
}

void Dynamics::eval_dynamics(double t, const double* q, const double* v) {
  load_inputs(t, q, v);
  dyn_.eval(in_.data(), out_.data(), work_.data());
}

void Dynamics::assemble_G() {
  const CompiledModel& cm = *model_;
  const double* g = out_.data() + cm.G_out();
  for (size_t e = 0; e < cm.G_pattern.size(); ++e)
    G_(static_cast<long>(cm.G_pattern[e].first), static_cast<long>(cm.G_pattern[e].second)) = g[e];
}

void Dynamics::fail_singular(double t, const std::string& what) const {
  const CompiledModel& cm = *model_;
  throw SimulationError(
      t, fmt::format("{} at state {}; {}", what,
                     format_values(cm.coordinate_names, in_.data() + cm.q_offset(), ""),
                     format_values(cm.coordinate_names, in_.data() + cm.v_offset(), "_dot")));
}

// DESIGN.md §4.3, range-space solution of the KKT system:
//   a₀ = M⁻¹(h + Q), Y = M⁻¹Gᵀ, (G Y) λ = G a₀ − γ, a = a₀ − Y λ,  γ = −c − 2αĊ − α²C.
void Dynamics::forward(double t, const double* q, const double* v, double* qdot, double* a,
                       double* lambda) {
  const CompiledModel& cm = *model_;
  eval_dynamics(t, q, v);
  const double* out = out_.data();
  for (size_t e = 0; e < cm.M_pattern.size(); ++e) {
    const auto [i, j] = cm.M_pattern[e];
    M_(static_cast<long>(i), static_cast<long>(j)) = out[e];
    M_(static_cast<long>(j), static_cast<long>(i)) = out[e];
  }
  for (size_t i = 0; i < cm.n; ++i) {
    rhs_[static_cast<long>(i)] = out[cm.rhs_out() + i];
    qdot[i] = out[cm.qdot_out() + i];
  }
  llt_M_.compute(M_);
  if (ill_conditioned(llt_M_, M_)) fail_singular(t, "the mass matrix is singular or indefinite");
  a_ = rhs_;
  llt_M_.solveInPlace(a_);
  if (cm.m > 0) {
    assemble_G();
    for (size_t r = 0; r < cm.m; ++r)
      gamma_[static_cast<long>(r)] = -out[cm.c_out() + r] -
                                     2.0 * alpha_ * out[cm.Cdot_out() + r] -
                                     alpha_ * alpha_ * out[cm.C_out() + r];
    Y_ = G_.transpose();
    llt_M_.solveInPlace(Y_);
    S_.noalias() = G_ * Y_;
    llt_S_.compute(S_);
    if (ill_conditioned(llt_S_, S_)) {
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(G_.transpose());
      std::string names;
      const auto perm = qr.colsPermutation().indices();
      for (long r = qr.rank(); r < perm.size(); ++r)
        names += (names.empty() ? "'" : ", '") + cm.constraint_names[static_cast<size_t>(perm[r])] + "'";
      fail_singular(t, fmt::format("the constraints are redundant or singular (rank {} of {}; "
                                   "dependent: {})",
                                   qr.rank(), cm.m, names.empty() ? "ill-conditioned" : names));
    }
    lambda_.noalias() = G_ * a_;
    lambda_ -= gamma_;
    llt_S_.solveInPlace(lambda_);
    a_.noalias() -= Y_ * lambda_;
    for (size_t r = 0; r < cm.m; ++r) lambda[r] = lambda_[static_cast<long>(r)];
  }
  for (size_t i = 0; i < cm.n; ++i) {
    a[i] = a_[static_cast<long>(i)];
    if (!std::isfinite(a[i]) || !std::isfinite(qdot[i]))
      fail_singular(t, fmt::format("the acceleration of '{}' is not finite", cm.coordinate_names[i]));
  }
}

void Dynamics::observe(double t, const double* q, const double* v, double* out) {
  load_inputs(t, q, v);
  obs_.eval(in_.data(), out, work_.data());
}

void Dynamics::constraints(double t, const double* q, const double* v, double* C, double* Cdot) {
  const CompiledModel& cm = *model_;
  eval_dynamics(t, q, v);
  for (size_t r = 0; r < cm.m; ++r) {
    C[r] = out_[cm.C_out() + r];
    Cdot[r] = out_[cm.Cdot_out() + r];
  }
}

}  // namespace lagrange
