// Exact derivatives of the dynamics (docs/theory.md §5.1): symbolic differentiation of the
// derived equations onto one tape, and the differentiated KKT system solved at a state.

#include <fmt/format.h>

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <algorithm>
#include <map>

#include "symbolic/memo_diff.hpp"
#include "lagrange/analysis.hpp"

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

// [M Gᵀ; G 0] X = R by a sparse LU (COLAMD ordering, threshold partial pivoting; the matrix is
// indefinite). AnalysisError when it is singular or the solution of a finite R is not finite.
Eigen::MatrixXd sparse_kkt_solve(const Eigen::MatrixXd& M, const Eigen::MatrixXd& G,
                                 const Eigen::MatrixXd& R, double t) {
  const long n = M.rows(), m = G.rows();
  std::vector<Eigen::Triplet<double>> entries;
  for (long j = 0; j < n; ++j)
    for (long i = 0; i < n; ++i)
      if (M(i, j) != 0.0) entries.emplace_back(i, j, M(i, j));
  for (long j = 0; j < n; ++j)
    for (long r = 0; r < m; ++r)
      if (G(r, j) != 0.0) {
        entries.emplace_back(n + r, j, G(r, j));
        entries.emplace_back(j, n + r, G(r, j));
      }
  Eigen::SparseMatrix<double> K(n + m, n + m);
  K.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  lu.compute(K);
  Eigen::MatrixXd X;
  if (lu.info() == Eigen::Success) X = lu.solve(R);
  // A right-hand side that is not finite (a derivative of |x| at 0) passes through to the
  // caller, which says the dynamics are not differentiable there.
  if (lu.info() != Eigen::Success || (!X.allFinite() && R.allFinite()))
    throw AnalysisError(
        fmt::format("the KKT matrix [M Gᵀ; G 0] is singular at t = {}: redundant constraints "
                    "or a mass matrix singular on the constraint manifold",
                    t));
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
}

// docs/theory.md §5.1: differentiating M a + Gᵀλ = f, G a = γ (γ = −c − 2αĊ − α²C) along a
// column x gives [M Gᵀ; G 0][a'; λ'] = [f' − M'a − G'ᵀλ; γ' − G'a], one solve for all columns.
StateJacobian DynamicsJacobian::evaluate(Dynamics& dyn, double t, const double* q,
                                         const double* v) const {
  const CompiledModel& c = *cm_;
  const long n = static_cast<long>(c.nv), m = static_cast<long>(c.m);
  const long nq = static_cast<long>(c.nq), nw = static_cast<long>(input_names_.size());
  const long ny = static_cast<long>(outputs_);
  StateJacobian J;
  J.qdot.resize(nq);
  J.a.resize(n);
  J.lambda.resize(m);
  dyn.forward(t, q, v, J.qdot.data(), J.a.data(), J.lambda.data());
  const double alpha = dyn.baumgarte();

  std::vector<double> out(tape_.num_outputs()), work(std::max<size_t>(tape_.work_size(), 1));
  tape_.eval(dyn.last_inputs().data(), out.data(), work.data());

  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
  for (size_t e = 0; e < c.M_pattern.size(); ++e) {
    const long i = static_cast<long>(c.M_pattern[e].first);
    const long j = static_cast<long>(c.M_pattern[e].second);
    M(i, j) = M(j, i) = out[e];
  }
  J.G = Eigen::MatrixXd::Zero(m, n);
  for (size_t e = 0; e < c.G_pattern.size(); ++e)
    J.G(static_cast<long>(c.G_pattern[e].first), static_cast<long>(c.G_pattern[e].second)) =
        out[c.G_out() + e];
  J.y.resize(ny);
  for (long k = 0; k < ny; ++k) J.y[k] = out[c.Cq_out() + static_cast<size_t>(k)];

  const long cols = static_cast<long>(columns_.size());
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(n + m, cols), Y = Eigen::MatrixXd::Zero(ny, cols);
  J.C_q = Eigen::MatrixXd::Zero(m, nq);
  J.Cdot_q = Eigen::MatrixXd::Zero(m, nq);
  J.qdot_q = Eigen::MatrixXd::Zero(nq, nq);
  J.qdot_v = Eigen::MatrixXd::Zero(nq, n);
  for (size_t e = 0; e < pattern_.size(); ++e) {
    const size_t r = pattern_[e].first;
    const long k = static_cast<long>(pattern_[e].second);
    const double d = out[values_ + e];
    if (r < c.rhs_out()) {  // M' a
      const long i = static_cast<long>(c.M_pattern[r].first);
      const long j = static_cast<long>(c.M_pattern[r].second);
      R(i, k) -= d * J.a[j];
      if (i != j) R(j, k) -= d * J.a[i];
    } else if (r < c.qdot_out()) {  // f'
      R(static_cast<long>(r - c.rhs_out()), k) += d;
    } else if (r < c.G_out()) {  // q̇'
      const long row = static_cast<long>(r - c.qdot_out());
      if (k < nq)
        J.qdot_q(row, k) = d;
      else if (k < nq + n)
        J.qdot_v(row, k - nq) = d;
    } else if (r < c.c_out()) {  // G'ᵀλ and G'a
      const long row = static_cast<long>(c.G_pattern[r - c.G_out()].first);
      const long j = static_cast<long>(c.G_pattern[r - c.G_out()].second);
      R(j, k) -= d * J.lambda[row];
      R(n + row, k) -= d * J.a[j];
    } else if (r < c.Cdot_out()) {  // c'
      R(n + static_cast<long>(r - c.c_out()), k) -= d;
    } else if (r < c.C_out()) {  // Ċ'
      const long row = static_cast<long>(r - c.Cdot_out());
      R(n + row, k) -= 2.0 * alpha * d;
      if (k < nq) J.Cdot_q(row, k) = d;
    } else if (r < c.Cq_out()) {  // C'
      const long row = static_cast<long>(r - c.C_out());
      R(n + row, k) -= alpha * alpha * d;
      if (k < nq) J.C_q(row, k) = d;
    } else {  // the model's outputs
      Y(static_cast<long>(r - c.Cq_out()), k) = d;
    }
  }

  Eigen::MatrixXd X;
  if (m == 0) {
    Eigen::LLT<Eigen::MatrixXd> llt(M);
    const double scale = n ? M.diagonal().cwiseAbs().maxCoeff() : 1.0;
    if (llt.info() != Eigen::Success ||
        (n && !(llt.matrixLLT().diagonal().cwiseAbs2().minCoeff() > 1e-13 * scale)))
      throw AnalysisError(fmt::format("the mass matrix is singular at t = {}", t));
    X = llt.solve(R);
  } else if (n + m > kSparseKkt) {
    X = sparse_kkt_solve(M, J.G, R, t);
  } else {
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + m, n + m);
    K.topLeftCorner(n, n) = M;
    K.topRightCorner(n, m) = J.G.transpose();
    K.bottomLeftCorner(m, n) = J.G;
    Eigen::PartialPivLU<Eigen::MatrixXd> lu(K);
    const auto d = lu.matrixLU().diagonal().cwiseAbs();
    if (!(d.minCoeff() > 1e-13 * d.maxCoeff()))
      throw AnalysisError(
          fmt::format("the KKT matrix [M Gᵀ; G 0] is singular at t = {}: redundant constraints "
                      "or a mass matrix singular on the constraint manifold",
                      t));
    X = lu.solve(R);
  }
  J.a_q = X.topLeftCorner(n, nq);
  J.a_v = X.block(0, nq, n, n);
  J.a_w = X.topRightCorner(n, nw);
  J.y_q = Y.leftCols(nq);
  J.y_v = Y.block(0, nq, ny, n);
  J.y_w = Y.rightCols(nw);
  return J;
}

}  // namespace lagrange
