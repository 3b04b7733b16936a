// Exact derivatives of the dynamics (docs/theory.md §5.1): symbolic differentiation of the
// derived equations onto one tape, and the differentiated KKT system solved at a state.

#include <fmt/format.h>

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <map>

#include "analysis/jacobian_limit.hpp"
#include "analysis/kkt_layout.hpp"
#include "dynamics/sparse_range_space.hpp"
#include "lagrange/analysis.hpp"
#include "symbolic/memo_diff.hpp"

namespace lagrange {

namespace {

// Tape input index of a named model input (u) or parameter.
size_t named_input(const CompiledModel& cm, const std::string& name) {
  const auto u = std::find(cm.input_names.begin(), cm.input_names.end(), name);
  if (u != cm.input_names.end())
    return cm.u_offset() + static_cast<size_t>(u - cm.input_names.begin());
  const auto p = std::find(cm.parameter_names.begin(), cm.parameter_names.end(), name);
  if (p != cm.parameter_names.end())
    return cm.p_offset() + static_cast<size_t>(p - cm.parameter_names.begin());
  std::string known;
  for (const auto& n : cm.input_names) known += (known.empty() ? "" : ", ") + n;
  for (const auto& n : cm.parameter_names) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument(
      fmt::format("no input or parameter '{}' in the model (expected one of: {})", name,
                  known.empty() ? "none" : known));
}

// Above this many KKT rows the differentiated system is factorised sparse: a tether's
// [M Gᵀ; G 0] is banded, and its dense LU with nq + nv right-hand sides cost more than central
// differences through the forward call at 200 segments (docs/benchmarks.md).
constexpr long kSparseKkt = 120;

[[noreturn]] void throw_singular(double t) {
  throw AnalysisError(
      fmt::format("the KKT matrix [M Gᵀ; G 0] is singular at t = {}: redundant constraints "
                  "or a mass matrix singular on the constraint manifold",
                  t));
}

// [M Gᵀ; G 0] X = R by a sparse LU (COLAMD ordering, threshold partial pivoting; the matrix is
// indefinite). AnalysisError when it is singular or the solution of a finite R is not finite.
Eigen::MatrixXd sparse_kkt_solve(const Eigen::SparseMatrix<double>& K, const Eigen::MatrixXd& R,
                                 double t) {
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  lu.compute(K);
  Eigen::MatrixXd X;
  if (lu.info() == Eigen::Success) X = lu.solve(R);
  // A right-hand side that is not finite (a derivative of |x| at 0) passes through to the
  // caller, which says the dynamics are not differentiable there.
  if (lu.info() != Eigen::Success || (!X.allFinite() && R.allFinite())) throw_singular(t);
  return X;
}

}  // namespace

DynamicsJacobian::DynamicsJacobian(const Equations& eq, std::shared_ptr<const CompiledModel> cm,
                                   const std::vector<std::string>& inputs,
                                   const std::vector<std::string>& outputs)
    : cm_(std::move(cm)), input_names_(inputs), output_names_(outputs) {
  const CompiledModel& c = *cm_;
  if (eq.recursive || !eq.definitions.empty())
    throw std::invalid_argument(
        "derivatives need the equations in Lagrangian form (M and h as expressions); derive "
        "with Formulation::Lagrangian");
  for (size_t i = 0; i < c.nq; ++i) columns_.push_back(c.q_offset() + i);
  for (size_t i = 0; i < c.nv; ++i) columns_.push_back(c.v_offset() + i);
  for (const auto& name : inputs) {
    const size_t index = named_input(c, name);
    if (std::find(columns_.begin(), columns_.end(), index) != columns_.end())
      throw std::invalid_argument(fmt::format("input '{}' named twice", name));
    columns_.push_back(index);
  }
  const std::vector<GiNaC::symbol> in = eq.tape_inputs();
  std::vector<GiNaC::symbol> column_symbols;
  for (size_t k : columns_) column_symbols.push_back(in[k]);
  symbolic::MemoDiff differentiate(column_symbols);
  // A parameter also acts through the prescribed inputs u(t, p), u̇, ü (Model::inputs):
  // d/dp = ∂/∂p + Σᵢ (∂/∂uᵢ ∂uᵢ/∂p + ∂/∂u̇ᵢ ∂u̇ᵢ/∂p + ∂/∂üᵢ ∂üᵢ/∂p). `through` holds, per
  // column, the (input symbol, ∂signal/∂p) pairs, and the input symbols point to those columns.
  const Model& model = *eq.model;
  std::vector<std::vector<std::pair<GiNaC::ex, GiNaC::ex>>> through(columns_.size());
  std::map<GiNaC::ex, std::vector<size_t>, GiNaC::ex_is_less> implies;
  for (size_t k = 0; k < columns_.size(); ++k) {
    if (columns_[k] < c.p_offset()) continue;
    const GiNaC::symbol& p = in[columns_[k]];
    for (const auto& u : model.inputs) {
      const GiNaC::ex signals[3] = {u.expr, u.expr.diff(model.t), u.expr.diff(model.t, 2)};
      const GiNaC::ex symbols[3] = {u.u, u.ud, u.udd};
      for (size_t d = 0; d < 3; ++d) {
        const GiNaC::ex ds = signals[d].diff(p);
        if (ds.is_zero()) continue;
        through[k].emplace_back(symbols[d], ds);
        implies[symbols[d]].push_back(k);
      }
    }
  }

  // Values: the dynamics tape's outputs up to (not including) ∂C/∂q, then the model's outputs.
  std::vector<GiNaC::ex> values = dynamics_expressions(eq, c);
  values.resize(c.Cq_out());
  for (const auto& name : outputs) {
    const auto it = std::find(c.output_names.begin(), c.output_names.end(), name);
    if (it == c.output_names.end()) {
      std::string known;
      for (const auto& n : c.output_names) known += (known.empty() ? "" : ", ") + n;
      throw std::invalid_argument(fmt::format("no output '{}' in the model (expected one of: {})",
                                              name, known.empty() ? "none" : known));
    }
    if (std::count(outputs.begin(), outputs.end(), name) > 1)
      throw std::invalid_argument(fmt::format("output '{}' named twice", name));
    values.push_back(eq.outputs[static_cast<size_t>(it - c.output_names.begin())]);
  }
  values_ = values.size();
  outputs_ = outputs.size();

  // docs/theory.md §5.1: ∂e/∂x for each value e and each column symbol it contains; q̇ too
  // (docs/theory.md §5.6: a free body's Ṙ = R(Ω + Ξ) for the first-order form's Jacobian).
  std::vector<GiNaC::ex> all = values;
  for (size_t r = 0; r < values.size(); ++r) {
    std::vector<size_t> cols = differentiate.columns_in(values[r]);
    for (const auto& [symbol, ks] : implies)
      if (values[r].has(symbol)) cols.insert(cols.end(), ks.begin(), ks.end());
    std::sort(cols.begin(), cols.end());
    cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
    for (size_t k : cols) {
      GiNaC::ex d = differentiate.diff(values[r], k);
      for (const auto& [symbol, ds] : through[k])
        d += values[r].diff(GiNaC::ex_to<GiNaC::symbol>(symbol)) * ds;
      if (d.is_zero()) continue;
      pattern_.emplace_back(r, k);
      all.push_back(d);
    }
  }
  tape_ = Tape::compile(all, in);
  layout_ = std::make_shared<analysis_detail::KktLayout>(c, pattern_, values_, columns_.size());
  range_space_ =
      c.m > 0 && static_cast<long>(c.nv + c.m) > kSparseKkt && dynamics::SparseRangeSpace::suits(c);
}

std::vector<double> DynamicsJacobian::values_at(Dynamics& dyn, double t, const double* q,
                                                const double* v, ImplicitJacobian& J) const {
  const CompiledModel& c = *cm_;
  J.qdot.resize(static_cast<long>(c.nq));
  J.a.resize(static_cast<long>(c.nv));
  J.lambda.resize(static_cast<long>(c.m));
  dyn.forward(t, q, v, J.qdot.data(), J.a.data(), J.lambda.data());
  std::vector<double> out(tape_.num_outputs()), work(std::max<size_t>(tape_.work_size(), 1));
  tape_.eval(dyn.last_inputs().data(), out.data(), work.data());
  return out;
}

ImplicitJacobian DynamicsJacobian::implicit(Dynamics& dyn, double t, const double* q,
                                            const double* v) const {
  ImplicitJacobian J;
  const std::vector<double> out = values_at(dyn, t, q, v, J);
  layout_->assemble(out.data(), J.a.data(), J.lambda.data(), dyn.baumgarte(), J);
  return J;
}

ImplicitJacobian DynamicsJacobian::implicit(Dynamics& dyn, double t, const double* q,
                                            const double* v, const double* a,
                                            const double* lambda) const {
  const CompiledModel& c = *cm_;
  const long nq = static_cast<long>(c.nq), n = static_cast<long>(c.nv), m = static_cast<long>(c.m);
  std::vector<double> C(c.m), Cdot(c.m);
  dyn.constraints(t, q, v, C.data(), Cdot.data());  // the dynamics tape's inputs at (t, q, v)
  std::vector<double> out(tape_.num_outputs()), work(std::max<size_t>(tape_.work_size(), 1));
  tape_.eval(dyn.last_inputs().data(), out.data(), work.data());
  ImplicitJacobian J;
  J.qdot = Eigen::Map<const Eigen::VectorXd>(out.data() + c.qdot_out(), nq);
  J.a = Eigen::Map<const Eigen::VectorXd>(a, n);
  J.lambda = Eigen::Map<const Eigen::VectorXd>(lambda, m);
  layout_->assemble(out.data(), a, lambda, dyn.baumgarte(), J);
  return J;
}

// docs/theory.md §5.1: differentiating M a + Gᵀλ = f, G a = γ (γ = −c − 2αĊ − α²C) along a
// column x gives [M Gᵀ; G 0][a'; λ'] = [f' − M'a − G'ᵀλ; γ' − G'a] = −∂Φ/∂x, one factorisation
// for all columns; with a block-diagonal M in range-space form, column by column on the sparse
// right-hand sides.
StateJacobian DynamicsJacobian::evaluate(Dynamics& dyn, double t, const double* q,
                                         const double* v) const {
  StateJacobian J = evaluate_here(dyn, t, q, v);
  const size_t nq = cm_->nq, n = nq + cm_->nv;
  std::vector<double> y(q, q + nq);
  y.insert(y.end(), v, v + cm_->nv);
  const auto at = [&](const double* moved) {
    StateJacobian M = evaluate_here(dyn, t, moved, moved + nq);
    std::vector<Eigen::MatrixXd> blocks;
    for (const Eigen::MatrixXd* B : analysis_detail::derivative_blocks(M)) blocks.push_back(*B);
    return blocks;
  };
  analysis_detail::fill_limits(analysis_detail::derivative_blocks(J), at, y.data(), n, t);
  return J;
}

StateJacobian DynamicsJacobian::evaluate_here(Dynamics& dyn, double t, const double* q,
                                              const double* v) const {
  const CompiledModel& c = *cm_;
  const long n = static_cast<long>(c.nv), m = static_cast<long>(c.m);
  const long nq = static_cast<long>(c.nq), nw = static_cast<long>(input_names_.size());
  const long ny = static_cast<long>(outputs_);
  ImplicitJacobian I;
  const std::vector<double> out = values_at(dyn, t, q, v, I);
  layout_->assemble(out.data(), I.a.data(), I.lambda.data(), dyn.baumgarte(), I);
  StateJacobian J;
  J.qdot = std::move(I.qdot);
  J.a = std::move(I.a);
  J.lambda = std::move(I.lambda);
  J.qdot_q = I.qdot_x.leftCols(nq);
  J.qdot_v = I.qdot_x.rightCols(n);
  J.G = Eigen::MatrixXd::Zero(m, n);
  for (size_t e = 0; e < c.G_pattern.size(); ++e)
    J.G(static_cast<long>(c.G_pattern[e].first), static_cast<long>(c.G_pattern[e].second)) =
        out[c.G_out() + e];
  J.y.resize(ny);
  for (long k = 0; k < ny; ++k) J.y[k] = out[c.Cq_out() + static_cast<size_t>(k)];

  // ∂C/∂q, ∂Ċ/∂q and the outputs' derivatives: the pattern is ordered by value index.
  const long cols = static_cast<long>(columns_.size());
  Eigen::MatrixXd Y = Eigen::MatrixXd::Zero(ny, cols);
  J.C_q = Eigen::MatrixXd::Zero(m, nq);
  J.Cdot_q = Eigen::MatrixXd::Zero(m, nq);
  const auto first =
      std::lower_bound(pattern_.begin(), pattern_.end(), std::make_pair(c.Cdot_out(), size_t{0}));
  for (auto it = first; it != pattern_.end(); ++it) {
    const auto [r, col] = *it;
    const long k = static_cast<long>(col);
    const double d = out[values_ + static_cast<size_t>(it - pattern_.begin())];
    if (r < c.C_out()) {
      if (k < nq) J.Cdot_q(static_cast<long>(r - c.Cdot_out()), k) = d;
    } else if (r < c.Cq_out()) {
      if (k < nq) J.C_q(static_cast<long>(r - c.C_out()), k) = d;
    } else {
      Y(static_cast<long>(r - c.Cq_out()), k) = d;
    }
  }

  J.a_q.resize(n, nq);
  J.a_v.resize(n, n);
  J.a_w.resize(n, nw);
  if (range_space_) {
    // Column blocks of kBlock right-hand sides, so that they stay in cache.
    dynamics::SparseRangeSpace kkt(c);
    const double* g = out.data() + c.G_out();
    if (!kkt.factorize(out.data(), g)) throw_singular(t);
    constexpr long kBlock = 64;
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    RowMajor R(n + m, kBlock), A(n, kBlock);
    bool finite = true;
    for (long k0 = 0; k0 < cols; k0 += kBlock) {
      const long kc = std::min(kBlock, cols - k0);
      R.setZero();
      for (long k = 0; k < kc; ++k)
        for (Eigen::SparseMatrix<double>::InnerIterator e(I.Phi_x, k0 + k); e; ++e) {
          R(e.row(), k) = -e.value();
          finite = finite && std::isfinite(e.value());
        }
      kkt.solve_factored(g, static_cast<size_t>(kBlock), R.data(), R.data() + n * kBlock, A.data());
      for (long k = 0; k < kc; ++k) {
        const long col = k0 + k;
        (col < nq       ? J.a_q.col(col)
         : col < nq + n ? J.a_v.col(col - nq)
                        : J.a_w.col(col - nq - n)) = A.col(k);
      }
    }
    if (finite && !(J.a_q.allFinite() && J.a_v.allFinite() && J.a_w.allFinite())) throw_singular(t);
  } else {
    Eigen::MatrixXd X(n, cols);  // ∂a/∂(q, v, w)
    if (m == 0) {
      const Eigen::MatrixXd M = I.K;
      Eigen::LLT<Eigen::MatrixXd> llt(M);
      const double scale = n ? M.diagonal().cwiseAbs().maxCoeff() : 1.0;
      if (llt.info() != Eigen::Success ||
          (n && !(llt.matrixLLT().diagonal().cwiseAbs2().minCoeff() > 1e-13 * scale)))
        throw AnalysisError(fmt::format("the mass matrix is singular at t = {}", t));
      X = llt.solve(-Eigen::MatrixXd(I.Phi_x));
    } else if (n + m > kSparseKkt) {
      X = sparse_kkt_solve(I.K, -Eigen::MatrixXd(I.Phi_x), t).topRows(n);
    } else {
      Eigen::PartialPivLU<Eigen::MatrixXd> lu(Eigen::MatrixXd(I.K));
      const auto d = lu.matrixLU().diagonal().cwiseAbs();
      if (!(d.minCoeff() > 1e-13 * d.maxCoeff())) throw_singular(t);
      X = lu.solve(-Eigen::MatrixXd(I.Phi_x)).topRows(n);
    }
    J.a_q = X.leftCols(nq);
    J.a_v = X.middleCols(nq, n);
    J.a_w = X.rightCols(nw);
  }
  J.y_q = Y.leftCols(nq);
  J.y_v = Y.block(0, nq, ny, n);
  J.y_w = Y.rightCols(nw);
  return J;
}

}  // namespace lagrange
