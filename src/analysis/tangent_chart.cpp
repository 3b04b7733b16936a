// Tangent coordinates of the positions (docs/theory.md §5.2): one per velocity, a free body's
// rotation as a local rotation vector δθ with R = R₀ exp([δθ]×).

#include <cmath>

#include "lagrange/analysis.hpp"

namespace lagrange {

namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& w) {
  Eigen::Matrix3d S;
  S << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return S;
}

// Free body b's first velocity (ṙ, then ω) and its R11 in q.
size_t body_velocity(const CompiledModel& cm, size_t b) {
  return cm.plain + 6 * b;
}

}  // namespace

TangentChart tangent_chart(const CompiledModel& cm, const double* q, const double* v) {
  const long nq = static_cast<long>(cm.nq), n = static_cast<long>(cm.nv);
  TangentChart chart;
  chart.T = Eigen::MatrixXd::Zero(nq, n);
  chart.rate_x = Eigen::MatrixXd::Zero(n, n);
  for (size_t i = 0; i < cm.plain; ++i) {
    chart.names.push_back(cm.coordinate_names[i]);
    chart.T(static_cast<long>(i), static_cast<long>(i)) = 1.0;
  }
  for (size_t b = 0; b < cm.rotations.size(); ++b) {
    const size_t iR = cm.rotations[b], ir = iR - 3, iv = body_velocity(cm, b);
    const std::string& r11 = cm.coordinate_names[iR];
    const std::string body = r11.substr(0, r11.size() - 4);  // "<body>.R11"
    for (size_t k = 0; k < 3; ++k) {
      chart.names.push_back(cm.coordinate_names[ir + k]);
      chart.T(static_cast<long>(ir + k), static_cast<long>(iv + k)) = 1.0;
    }
    const Eigen::Matrix3d R =
        Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(q + iR);
    for (size_t k = 0; k < 3; ++k) {
      chart.names.push_back(body + ".dtheta_" + "xyz"[k]);
      // ∂R/∂δθ_k at δθ = 0 is R [e_k]×, R row-major in q.
      const Eigen::Matrix3d dR = R * skew(Eigen::Vector3d::Unit(static_cast<long>(k)));
      for (long i = 0; i < 3; ++i)
        for (long j = 0; j < 3; ++j)
          chart.T(static_cast<long>(iR) + 3 * i + j, static_cast<long>(iv + 3 + k)) = dR(i, j);
    }
    // δθ̇ = J_r(δθ)⁻¹ ω = ω + ½ δθ × ω + O(δθ²): ∂δθ̇/∂δθ = −½[ω]×.
    const Eigen::Vector3d w(v[iv + 3], v[iv + 4], v[iv + 5]);
    chart.rate_x.block<3, 3>(static_cast<long>(iv + 3), static_cast<long>(iv + 3)) = -0.5 * skew(w);
  }
  return chart;
}

void retract(const CompiledModel& cm, const double* dx, double* q) {
  for (size_t i = 0; i < cm.plain; ++i) q[i] += dx[i];
  for (size_t b = 0; b < cm.rotations.size(); ++b) {
    const size_t iR = cm.rotations[b], ir = iR - 3, iv = body_velocity(cm, b);
    for (size_t k = 0; k < 3; ++k) q[ir + k] += dx[iv + k];
    const Eigen::Vector3d th(dx[iv + 3], dx[iv + 4], dx[iv + 5]);
    const double angle = th.norm();
    Eigen::Matrix3d E = Eigen::Matrix3d::Identity();
    if (angle > 0) E = Eigen::AngleAxisd(angle, th / angle).toRotationMatrix();
    Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> R(q + iR);
    const Eigen::Matrix3d next = R * E;
    R = next;
  }
}

}  // namespace lagrange
