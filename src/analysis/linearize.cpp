// Linearisation on the constraint manifold (docs/theory.md §5.3).

#include <fmt/format.h>

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
// and the reduced model is A_r = S A W, B_r = S B (S selects the independent rows).
LinearModel linearize(const DynamicsJacobian& jac, Dynamics& dyn, double t, const double* q,
                      const double* v, const std::vector<std::string>& outputs) {
  const CompiledModel& cm = jac.model();
  const long n = static_cast<long>(cm.nv), m = static_cast<long>(cm.m);
  const StateJacobian J = jac.evaluate(dyn, t, q, v);
  const TangentChart chart = tangent_chart(cm, q, v);

  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  A.topLeftCorner(n, n) = chart.rate_x;
  A.topRightCorner(n, n).setIdentity();
  A.bottomLeftCorner(n, n) = J.a_q * chart.T;
  A.bottomRightCorner(n, n) = J.a_v;
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(2 * n, J.a_w.cols());
  B.bottomRows(n) = J.a_w;

  LinearModel lin;
  lin.input_names = jac.input_names();
  lin.full_state_names = chart.names;
  lin.full_state_names.insert(lin.full_state_names.end(), cm.velocity_names.begin(),
                              cm.velocity_names.end());
  lin.equilibrium_residual = std::max(J.qdot.size() ? J.qdot.cwiseAbs().maxCoeff() : 0.0,
                                      J.a.size() ? J.a.cwiseAbs().maxCoeff() : 0.0);

  // Independent coordinates: column-pivoted QR of C_x = C_q T puts m well-conditioned dependent
  // coordinates first; their velocities are dependent too.
  std::vector<long> independent;
  Eigen::MatrixXd W;
  if (m == 0) {
    for (long i = 0; i < 2 * n; ++i) independent.push_back(i);
    W = Eigen::MatrixXd::Identity(2 * n, 2 * n);
  } else {
    const Eigen::MatrixXd Cx = J.C_q * chart.T;
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Cx);
    if (qr.rank() < m)
      throw AnalysisError(fmt::format(
          "the constraints are redundant at the operating point (rank {} of {})", qr.rank(), m));
    std::vector<bool> dep(static_cast<size_t>(n), false);
    for (long k = 0; k < m; ++k) dep[static_cast<size_t>(qr.colsPermutation().indices()[k])] = true;
    std::vector<long> d;
    for (long i = 0; i < n; ++i) (dep[static_cast<size_t>(i)] ? d : independent).push_back(i);
    for (long i : d) lin.dependent.push_back(chart.names[static_cast<size_t>(i)]);
    const size_t ni = independent.size();
    for (size_t k = 0; k < ni; ++k) independent.push_back(independent[k] + n);
    for (size_t k = 0; k < static_cast<size_t>(m); ++k) d.push_back(d[k] + n);
    Eigen::MatrixXd JM = Eigen::MatrixXd::Zero(2 * m, 2 * n);
    JM.topLeftCorner(m, n) = Cx;
    JM.bottomLeftCorner(m, n) = J.Cdot_q * chart.T;
    JM.bottomRightCorner(m, n) = J.G;
    const long r = static_cast<long>(independent.size());
    Eigen::MatrixXd Jd(2 * m, 2 * m), Ji(2 * m, r);
    for (long k = 0; k < 2 * m; ++k) Jd.col(k) = JM.col(d[static_cast<size_t>(k)]);
    for (long k = 0; k < r; ++k) Ji.col(k) = JM.col(independent[static_cast<size_t>(k)]);
    const Eigen::MatrixXd Zd = -Jd.partialPivLu().solve(Ji);
    W = Eigen::MatrixXd::Zero(2 * n, r);
    for (long k = 0; k < r; ++k) W(independent[static_cast<size_t>(k)], k) = 1.0;
    for (long k = 0; k < 2 * m; ++k) W.row(d[static_cast<size_t>(k)]) = Zd.row(k);
  }
  const long r = static_cast<long>(independent.size());
  require_finite(A, lin.full_state_names, lin.full_state_names, "A");
  require_finite(B, lin.full_state_names, lin.input_names, "B");
  lin.A.resize(r, r);
  lin.B.resize(r, B.cols());
  const Eigen::MatrixXd AW = A * W;
  for (long k = 0; k < r; ++k) {
    lin.A.row(k) = AW.row(independent[static_cast<size_t>(k)]);
    lin.B.row(k) = B.row(independent[static_cast<size_t>(k)]);
    lin.state_names.push_back(
        lin.full_state_names[static_cast<size_t>(independent[static_cast<size_t>(k)])]);
  }
  lin.basis = W;
  if (outputs.empty()) {
    lin.output_names = lin.state_names;
    lin.C = Eigen::MatrixXd::Identity(r, r);
    lin.D = Eigen::MatrixXd::Zero(r, B.cols());
  } else {
    lin.output_names = outputs;
    Eigen::MatrixXd Cfull;
    output_rows(jac, chart, J, outputs, Cfull, lin.D);
    lin.C = Cfull * W;
  }
  return lin;
}

}  // namespace lagrange
