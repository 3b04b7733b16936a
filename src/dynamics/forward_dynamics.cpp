#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "dynamics/native_tapes.hpp"
#include "dynamics/projection_workspace.hpp"
#include "dynamics/sparse_range_space.hpp"
#include "lagrange/dynamics.hpp"
#include "lagrange/error.hpp"

namespace lagrange {

namespace {

constexpr size_t kSparseThreshold = 24;  // coordinates; below it dense LLT is faster

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

// Plain coordinates are named by q ('x'), free-body velocities by their own name ('top.wx').
const std::string& acceleration_name(const CompiledModel& cm, size_t i) {
  return i < cm.plain ? cm.coordinate_names[i] : cm.velocity_names[i];
}

}  // namespace

Dynamics::Dynamics(std::shared_ptr<const CompiledModel> model,
                   const std::vector<double>& parameters)
    : model_(std::move(model)) {
  const CompiledModel& cm = *model_;
  in_.assign(cm.input_count(), 0.0);
  out_.assign(cm.dynamics.num_outputs(), 0.0);
  obs_out_.assign(cm.observables.num_outputs(), 0.0);
  sig_out_.assign(cm.inputs.num_outputs(), 0.0);
  M_.setZero(cm.nv, cm.nv);
  G_.setZero(cm.m, cm.nv);
  Y_.setZero(cm.nv, cm.m);
  S_.setZero(cm.m, cm.m);
  rhs_.setZero(cm.nv);
  a_.setZero(cm.nv);
  gamma_.setZero(cm.m);
  lambda_.setZero(cm.m);
  // Reserve the factorisations' storage by factorising identities (a moved-from, never
  // computed Eigen 3.4 LLT carries an uninitialised status, which UBSan rightly reports).
  llt_M_.compute(Eigen::MatrixXd::Identity(static_cast<long>(cm.nv), static_cast<long>(cm.nv)));
  llt_S_.compute(Eigen::MatrixXd::Identity(static_cast<long>(cm.m), static_cast<long>(cm.m)));
  K_.setZero(cm.nv + cm.m, cm.nv + cm.m);
  kkt_rhs_.setZero(cm.nv + cm.m);
  lu_K_.compute(
      Eigen::MatrixXd::Identity(static_cast<long>(cm.nv + cm.m), static_cast<long>(cm.nv + cm.m)));
  // A block-diagonal M with many constraints (chains in Cartesian coordinates, free bodies on
  // them) takes the sparse range-space path; small systems stay dense, where it is faster.
  if (cm.m > 0 && cm.nv >= kSparseThreshold && dynamics::SparseRangeSpace::suits(cm))
    sparse_ = std::make_unique<dynamics::SparseRangeSpace>(cm);
  set_parameters(parameters);
}

Dynamics::~Dynamics() = default;
Dynamics::Dynamics(Dynamics&&) noexcept = default;
Dynamics& Dynamics::operator=(Dynamics&&) noexcept = default;

void Dynamics::set_parameters(const std::vector<double>& values) {
  const CompiledModel& cm = *model_;
  if (values.size() != cm.np)
    throw std::invalid_argument(
        fmt::format("expected {} parameter values, got {}", cm.np, values.size()));
  params_ = values;
  std::copy(params_.begin(), params_.end(), in_.begin() + static_cast<long>(cm.p_offset()));
  // docs/theory.md §8: specialise the tapes to the parameter values by constant folding.
  dyn_ = cm.dynamics.specialize(cm.p_offset(), params_);
  obs_ = cm.observables.specialize(cm.p_offset(), params_);
  sig_ = cm.inputs.specialize(cm.p_offset(), params_);
  work_.assign(std::max({dyn_.work_size(), obs_.work_size(), sig_.work_size(), size_t{1}}), 0.0);
  refresh_machine_code();
}

// Machine code when it is ready, else the interpreter: the same bits either way (§8).
void Dynamics::run(size_t slot, const Tape& tape, double* out) {
  if (native_) {
    if (const auto f = native_->function(static_cast<dynamics::TapeSlot>(slot))) {
      f(in_.data(), out, work_.data());
      return;
    }
  }
  tape.eval(in_.data(), out, work_.data());
}

void Dynamics::load_inputs(double t, const double* q, const double* v) {
  const CompiledModel& cm = *model_;
  in_[0] = t;
  std::copy(q, q + cm.nq, in_.begin() + static_cast<long>(cm.q_offset()));
  std::copy(v, v + cm.nv, in_.begin() + static_cast<long>(cm.v_offset()));
  if (cm.k > 0) {
    run(dynamics::kInputsTape, sig_, sig_out_.data());
    std::copy(sig_out_.begin(), sig_out_.end(), in_.begin() + static_cast<long>(cm.u_offset()));
    if (law_) law_(t, q, v, law_values_.data());
    const auto set = [&](size_t i, double value) {
      in_[cm.u_offset() + i] = value;
      in_[cm.u_offset() + cm.k + i] = 0.0;
      in_[cm.u_offset() + 2 * cm.k + i] = 0.0;
    };
    for (const auto& [i, value] : held_) set(i, value);
    for (size_t j = 0; j < law_inputs_.size(); ++j) set(law_inputs_[j], law_values_[j]);
  }
}

void Dynamics::set_input_law(std::vector<size_t> indices, InputLaw law) {
  for (size_t i : indices)
    if (i >= model_->k)
      throw std::out_of_range(
          fmt::format("set_input_law: input {} of a model with {} inputs", i, model_->k));
  law_values_.assign(law ? indices.size() : 0, 0.0);
  law_inputs_ = law ? std::move(indices) : std::vector<size_t>{};
  law_ = std::move(law);
}

void Dynamics::release_inputs() {
  held_.clear();
  set_input_law({}, nullptr);
}

void Dynamics::hold_input(size_t index, double value) {
  if (index >= model_->k)
    throw std::out_of_range(
        fmt::format("hold_input: input {} of a model with {} inputs", index, model_->k));
  for (auto& held : held_)
    if (held.first == index) {
      held.second = value;
      return;
    }
  held_.emplace_back(index, value);
}

void Dynamics::eval_dynamics(double t, const double* q, const double* v) {
  load_inputs(t, q, v);
  run(dynamics::kDynamicsTape, dyn_, out_.data());
}

void Dynamics::assemble_G() {
  const CompiledModel& cm = *model_;
  const double* g = out_.data() + cm.G_out();
  for (size_t e = 0; e < cm.G_pattern.size(); ++e)
    G_(static_cast<long>(cm.G_pattern[e].first), static_cast<long>(cm.G_pattern[e].second)) = g[e];
}

void Dynamics::assemble_M() {
  const CompiledModel& cm = *model_;
  for (size_t e = 0; e < cm.M_pattern.size(); ++e) {
    const long i = static_cast<long>(cm.M_pattern[e].first);
    const long j = static_cast<long>(cm.M_pattern[e].second);
    M_(i, j) = M_(j, i) = out_[e];
  }
}

void Dynamics::fail_singular(double t, const std::string& what) const {
  const CompiledModel& cm = *model_;
  throw SimulationError(
      t, fmt::format("{} at state {}; {}", what,
                     format_values(cm.coordinate_names, in_.data() + cm.q_offset(), ""),
                     format_values(cm.velocity_names, in_.data() + cm.v_offset(), "")));
}

void Dynamics::fail_redundant(double t) const {
  const CompiledModel& cm = *model_;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(G_.transpose());
  std::string names;
  const auto perm = qr.colsPermutation().indices();
  for (long r = qr.rank(); r < perm.size(); ++r)
    names +=
        (names.empty() ? "'" : ", '") + cm.constraint_names[static_cast<size_t>(perm[r])] + "'";
  if (names.empty())
    fail_singular(t,
                  "the mass matrix is singular on the constraint manifold (the KKT system "
                  "has no unique solution)");
  fail_singular(t, fmt::format("the constraints are redundant or singular (rank {} of {}; "
                               "dependent: {})",
                               qr.rank(), cm.m, names));
}

// docs/theory.md §4.3, range-space solution of the KKT system:
//   a₀ = M⁻¹(h + Q), Y = M⁻¹Gᵀ, (G Y) λ = G a₀ − γ, a = a₀ − Y λ,  γ = −c − 2αĊ − α²C.
// When M alone is singular (a coordinate whose inertia only the constraints supply) the
// whole symmetric KKT matrix is factorised instead.
void Dynamics::forward(double t, const double* q, const double* v, double* qdot, double* a,
                       double* lambda) {
  const CompiledModel& cm = *model_;
  eval_dynamics(t, q, v);
  const double* out = out_.data();
  // A non-finite acceleration: named at the generalised forces or the constraint terms when an
  // expression of the model is not finite there (x^(5/2) at x < 0), else at the acceleration.
  const auto not_finite = [&](size_t i) {
    for (size_t j = 0; j < cm.nv; ++j)
      if (!std::isfinite(out[cm.rhs_out() + j]))
        fail_singular(t, fmt::format("the generalised forces on '{}' are not finite (an "
                                     "expression of the model has no finite value here)",
                                     acceleration_name(cm, j)));
    for (size_t r = 0; r < cm.m; ++r)
      if (!std::isfinite(gamma_[static_cast<long>(r)]))
        fail_singular(
            t, fmt::format("the terms of constraint '{}' are not finite", cm.constraint_names[r]));
    fail_singular(t,
                  fmt::format("the acceleration of '{}' is not finite", acceleration_name(cm, i)));
  };
  for (size_t i = 0; i < cm.nq; ++i) {
    qdot[i] = out[cm.qdot_out() + i];
    if (!std::isfinite(qdot[i]))
      fail_singular(t, fmt::format("the rate of '{}' is not finite", cm.coordinate_names[i]));
  }
  for (size_t r = 0; r < cm.m; ++r)
    gamma_[static_cast<long>(r)] = -out[cm.c_out() + r] - 2.0 * alpha_ * out[cm.Cdot_out() + r] -
                                   alpha_ * alpha_ * out[cm.C_out() + r];
  // The sparse path reads M, G and h + Q where the tape left them: no dense M or G to fill.
  if (sparse_) {
    if (sparse_->solve(out, out + cm.G_out(), out + cm.rhs_out(), gamma_.data(), a, lambda)) {
      for (size_t i = 0; i < cm.nv; ++i)
        if (!std::isfinite(a[i])) not_finite(i);
      return;
    }  // otherwise the dense path below diagnoses the failure
  }
  assemble_M();
  for (size_t i = 0; i < cm.nv; ++i) rhs_[static_cast<long>(i)] = out[cm.rhs_out() + i];
  if (cm.m > 0) assemble_G();
  if (cm.m == 0 && cm.M_diagonal && cm.nv > 0) {
    // A diagonal M (among them the recursive formulation's M = 1, docs/theory.md §4.9):
    // a = (h + Q)/Mᵢᵢ, under the Cholesky path's conditioning test (pivot² = Mᵢᵢ).
    const double scale = M_.diagonal().cwiseAbs().maxCoeff();
    for (size_t i = 0; i < cm.nv; ++i) {
      const double d = M_(static_cast<long>(i), static_cast<long>(i));
      if (!(d > 1e-13 * scale)) fail_singular(t, "the mass matrix is singular or indefinite");
      a[i] = rhs_[static_cast<long>(i)] / d;
      if (!std::isfinite(a[i])) not_finite(i);
    }
    return;
  }
  llt_M_.compute(M_);
  if (ill_conditioned(llt_M_, M_)) {
    if (cm.m == 0) fail_singular(t, "the mass matrix is singular or indefinite");
    solve_full_kkt(t);
  } else {
    a_ = rhs_;
    llt_M_.solveInPlace(a_);
    if (cm.m > 0) {
      Y_ = G_.transpose();
      llt_M_.solveInPlace(Y_);
      S_.noalias() = G_ * Y_;
      llt_S_.compute(S_);
      if (ill_conditioned(llt_S_, S_)) fail_redundant(t);
      lambda_.noalias() = G_ * a_;
      lambda_ -= gamma_;
      llt_S_.solveInPlace(lambda_);
      a_.noalias() -= Y_ * lambda_;
    }
  }
  for (size_t r = 0; r < cm.m; ++r) lambda[r] = lambda_[static_cast<long>(r)];
  for (size_t i = 0; i < cm.nv; ++i) {
    a[i] = a_[static_cast<long>(i)];
    if (!std::isfinite(a[i])) not_finite(i);
  }
}

// [M Gᵀ; G 0][a; λ] = [h + Q; γ] by LU with partial pivoting (docs/theory.md §4.3).
void Dynamics::solve_full_kkt(double t) {
  const CompiledModel& cm = *model_;
  const long n = static_cast<long>(cm.nv), m = static_cast<long>(cm.m);
  K_.topLeftCorner(n, n) = M_;
  K_.topRightCorner(n, m) = G_.transpose();
  K_.bottomLeftCorner(m, n) = G_;
  K_.bottomRightCorner(m, m).setZero();
  kkt_rhs_.head(n) = rhs_;
  kkt_rhs_.tail(m) = gamma_;
  lu_K_.compute(K_);
  const auto d = lu_K_.matrixLU().diagonal().cwiseAbs();
  if (!(d.minCoeff() > 1e-13 * d.maxCoeff())) fail_redundant(t);
  kkt_rhs_ = lu_K_.solve(kkt_rhs_);
  a_ = kkt_rhs_.head(n);
  lambda_ = kkt_rhs_.tail(m);
}

// docs/theory.md §4.3: M v' and G v', Gᵀλ from the tape's structural non-zeros (no dense
// products: M and G of many coordinates are mostly zeros).
void Dynamics::dae_residual(double t, const double* q, const double* v, const double* qp,
                            const double* vp, const double* lambda, double* r) {
  const CompiledModel& cm = *model_;
  const size_t nq = cm.nq, n = cm.nv, m = cm.m;
  eval_dynamics(t, q, v);
  const double* out = out_.data();
  double* rv = r + nq;
  double* rl = r + nq + n;
  for (size_t i = 0; i < nq; ++i) r[i] = qp[i] - out[cm.qdot_out() + i];
  for (size_t i = 0; i < n; ++i) rv[i] = -out[cm.rhs_out() + i];
  for (size_t e = 0; e < cm.M_pattern.size(); ++e) {  // upper triangle of the symmetric M
    const auto [i, j] = cm.M_pattern[e];
    rv[i] += out[e] * vp[j];
    if (i != j) rv[j] += out[e] * vp[i];
  }
  for (size_t k = 0; k < m; ++k)
    rl[k] = out[cm.c_out() + k] + 2.0 * alpha_ * out[cm.Cdot_out() + k] +
            alpha_ * alpha_ * out[cm.C_out() + k];
  const double* g = out + cm.G_out();
  for (size_t e = 0; e < cm.G_pattern.size(); ++e) {
    const auto [k, j] = cm.G_pattern[e];
    rv[j] += g[e] * lambda[k];
    rl[k] += g[e] * vp[j];
  }
}

void Dynamics::observe(double t, const double* q, const double* v, double* out) {
  load_inputs(t, q, v);
  run(dynamics::kObservablesTape, obs_, out);
}

void Dynamics::constraints(double t, const double* q, const double* v, double* C, double* Cdot) {
  eval_dynamics(t, q, v);
  last_constraints(C, Cdot);
}

void Dynamics::last_constraints(double* C, double* Cdot) const {
  const CompiledModel& cm = *model_;
  for (size_t r = 0; r < cm.m; ++r) {
    C[r] = out_[cm.C_out() + r];
    Cdot[r] = out_[cm.Cdot_out() + r];
  }
}

}  // namespace lagrange
