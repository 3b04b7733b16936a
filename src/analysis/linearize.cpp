// Linearisation on the constraint manifold (docs/theory.md §5.3).

#include <fmt/format.h>

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>

#include "lagrange/analysis.hpp"

namespace lagrange {

namespace {

long index_of(const std::vector<std::string>& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : static_cast<long>(it - names.begin());
}

// Rows of C (full tangent state) and D for the named outputs.
void output_rows(const DynamicsJacobian& jac, const TangentChart& chart, const StateJacobian& J,
                 const std::vector<std::string>& outputs, Eigen::MatrixXd& C, Eigen::MatrixXd& D) {
  const CompiledModel& cm = jac.model();
  const long n = static_cast<long>(cm.nv);
  C = Eigen::MatrixXd::Zero(static_cast<long>(outputs.size()), 2 * n);
  D = Eigen::MatrixXd::Zero(static_cast<long>(outputs.size()), J.a_w.cols());
  for (size_t r = 0; r < outputs.size(); ++r) {
    const long row = static_cast<long>(r);
    const std::string& name = outputs[r];
    if (const long i = index_of(chart.names, name); i >= 0) {
      C(row, i) = 1.0;
    } else if (const long j = index_of(cm.coordinate_names, name); j >= 0) {
      C.row(row).head(n) = chart.T.row(j);  // a rotation entry: δR_ij = (T δx)_ij
    } else if (const long k = index_of(cm.velocity_names, name); k >= 0) {
      C(row, n + k) = 1.0;
    } else if (const long y = index_of(jac.output_names(), name); y >= 0) {
      C.row(row).head(n) = J.y_q.row(y) * chart.T;
      C.row(row).tail(n) = J.y_v.row(y);
      D.row(row) = J.y_w.row(y);
    } else if (index_of(cm.output_names, name) >= 0) {
      throw std::invalid_argument(fmt::format(
          "output '{}' was not differentiated: name it among the DynamicsJacobian's outputs",
          name));
    } else {
      std::string known;
      for (const auto& s : chart.names) known += (known.empty() ? "" : ", ") + s;
      for (const auto& s : cm.velocity_names) known += ", " + s;
      for (const auto& s : cm.output_names) known += ", " + s;
      throw std::invalid_argument(fmt::format(
          "no output '{}' in the model (expected a coordinate, a velocity or an output: {})", name,
          known));
    }
  }
}

// A NaN or infinite derivative: the dynamics are not differentiable at the point (|x| at 0, a
// norm at the zero vector under a division, …); name the first entry.
void require_finite(const Eigen::MatrixXd& X, const std::vector<std::string>& rows,
                    const std::vector<std::string>& cols, const char* what) {
  for (long j = 0; j < X.cols(); ++j)
    for (long i = 0; i < X.rows(); ++i)
      if (!std::isfinite(X(i, j)))
        throw AnalysisError(fmt::format(
            "{} is not finite at the operating point (d {}/d {} = {}): the dynamics are not "
            "differentiable there",
            what, rows[static_cast<size_t>(i)], cols[static_cast<size_t>(j)], X(i, j)));
}

}  // namespace

// docs/theory.md §5.3: full tangent state z = (δx, δv), ż = A z + B w with
//   A = [∂ẋ/∂x  1; (∂a/∂q) T  ∂a/∂v],  B = [0; ∂a/∂w];
// on {C = 0, Ċ = 0} the dependent coordinates d follow from J_M z = 0,
//   J_M = [C_q T  0; Ċ_q T  G],  z_d = −J_M,d⁻¹ J_M,i z_i  (z = W z_i),
// and the reduced model is A_r = S A W, B_r = S B (S selects the independent rows). J_M,d is
// block lower triangular and A's top rows are [∂ẋ/∂x 1], so A_r is formed from blocks of
// size (n − m) × m (docs/theory.md §5.3, "Cost").
LinearModel linearize(const DynamicsJacobian& jac, Dynamics& dyn, double t, const double* q,
                      const double* v, const std::vector<std::string>& outputs) {
  const CompiledModel& cm = jac.model();
  const long n = static_cast<long>(cm.nv), m = static_cast<long>(cm.m);
  const StateJacobian J = jac.evaluate(dyn, t, q, v);
  const TangentChart chart = tangent_chart(cm, q, v);
  const Eigen::SparseMatrix<double> T = chart.T.sparseView();
  const Eigen::SparseMatrix<double> rate = chart.rate_x.sparseView();
  const Eigen::MatrixXd Ax = J.a_q * T;

  LinearModel lin;
  lin.input_names = jac.input_names();
  lin.full_state_names = chart.names;
  lin.full_state_names.insert(lin.full_state_names.end(), cm.velocity_names.begin(),
                              cm.velocity_names.end());
  lin.equilibrium_residual = std::max(J.qdot.size() ? J.qdot.cwiseAbs().maxCoeff() : 0.0,
                                      J.a.size() ? J.a.cwiseAbs().maxCoeff() : 0.0);
  require_finite(Ax, cm.velocity_names, chart.names, "A");
  require_finite(J.a_v, cm.velocity_names, cm.velocity_names, "A");
  require_finite(J.a_w, cm.velocity_names, lin.input_names, "B");

  // Independent coordinates i: column-pivoted QR of C_x = C_q T puts m well-conditioned
  // dependent coordinates d first; their velocities are dependent too.
  std::vector<long> d, independent;
  Eigen::MatrixXd Cx;
  if (m > 0) {
    Cx = J.C_q * T;
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Cx);
    if (qr.rank() < m)
      throw AnalysisError(fmt::format(
          "the constraints are redundant at the operating point (rank {} of {})", qr.rank(), m));
    std::vector<bool> dep(static_cast<size_t>(n), false);
    for (long k = 0; k < m; ++k) dep[static_cast<size_t>(qr.colsPermutation().indices()[k])] = true;
    for (long i = 0; i < n; ++i) (dep[static_cast<size_t>(i)] ? d : independent).push_back(i);
  } else {
    for (long i = 0; i < n; ++i) independent.push_back(i);
  }
  for (long i : d) lin.dependent.push_back(chart.names[static_cast<size_t>(i)]);
  const long ni = static_cast<long>(independent.size()), r = 2 * ni;

  // z_d = W_d z_i: positions δx_d = Z1 δx_i (C_x δx = 0), velocities
  // δv_d = Z2 δx_i + Z3 δv_i (Ċ_x δx + G δv = 0).
  Eigen::MatrixXd Z1(m, ni), Z2(m, ni), Z3(m, ni);
  if (m > 0) {
    const Eigen::MatrixXd Cdx = J.Cdot_q * T;
    const Eigen::PartialPivLU<Eigen::MatrixXd> Cd(Cx(Eigen::all, d));
    const Eigen::PartialPivLU<Eigen::MatrixXd> Gd(J.G(Eigen::all, d));
    Z1 = -Cd.solve(Cx(Eigen::all, independent));
    Z2 = -Gd.solve(Cdx(Eigen::all, independent) + Cdx(Eigen::all, d) * Z1);
    Z3 = -Gd.solve(J.G(Eigen::all, independent));
  }
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(2 * n, r);
  for (long k = 0; k < ni; ++k) {
    W(independent[static_cast<size_t>(k)], k) = 1.0;
    W(n + independent[static_cast<size_t>(k)], ni + k) = 1.0;
  }
  for (long k = 0; k < m; ++k) {
    const long row = d[static_cast<size_t>(k)];
    W.row(row).head(ni) = Z1.row(k);
    W.row(n + row).head(ni) = Z2.row(k);
    W.row(n + row).tail(ni) = Z3.row(k);
  }

  // A_r = S A W: position rows (∂ẋ/∂x W_x + W_v)_i, velocity rows
  // [Ax_ii + Ax_id Z1 + a_v,id Z2,  a_v,ii + a_v,id Z3].
  lin.A.resize(r, r);
  lin.A.setZero();
  if (rate.nonZeros() > 0) lin.A.topRows(ni) = (rate * W.topRows(n))(independent, Eigen::all);
  lin.A.block(0, ni, ni, ni) += Eigen::MatrixXd::Identity(ni, ni);
  const Eigen::MatrixXd av_id = J.a_v(independent, d);
  lin.A.bottomLeftCorner(ni, ni) = Ax(independent, independent);
  lin.A.bottomRightCorner(ni, ni) = J.a_v(independent, independent);
  if (m > 0) {
    lin.A.bottomLeftCorner(ni, ni) += Ax(independent, d) * Z1 + av_id * Z2;
    lin.A.bottomRightCorner(ni, ni) += av_id * Z3;
  }
  lin.B = Eigen::MatrixXd::Zero(r, J.a_w.cols());
  lin.B.bottomRows(ni) = J.a_w(independent, Eigen::all);
  for (long k = 0; k < ni; ++k)
    lin.state_names.push_back(
        chart.names[static_cast<size_t>(independent[static_cast<size_t>(k)])]);
  for (long k = 0; k < ni; ++k)
    lin.state_names.push_back(
        cm.velocity_names[static_cast<size_t>(independent[static_cast<size_t>(k)])]);
  lin.basis = std::move(W);
  if (outputs.empty()) {
    lin.output_names = lin.state_names;
    lin.C = Eigen::MatrixXd::Identity(r, r);
    lin.D = Eigen::MatrixXd::Zero(r, lin.B.cols());
  } else {
    lin.output_names = outputs;
    Eigen::MatrixXd Cfull;
    output_rows(jac, chart, J, outputs, Cfull, lin.D);
    lin.C = Cfull * lin.basis;
  }
  return lin;
}

}  // namespace lagrange
