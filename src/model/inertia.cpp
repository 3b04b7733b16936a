#include <fmt/format.h>

#include <Eigen/Dense>
#include <cmath>
#include <optional>
#include <sstream>

#include "lagrange/rigid_body.hpp"

namespace lagrange {

Mat3 principal_inertia(const GiNaC::ex& ixx, const GiNaC::ex& iyy, const GiNaC::ex& izz) {
  return {Vec3{ixx, 0, 0}, Vec3{0, iyy, 0}, Vec3{0, 0, izz}};
}

Mat3 box_inertia(const GiNaC::ex& m, const GiNaC::ex& a, const GiNaC::ex& b, const GiNaC::ex& c) {
  return principal_inertia(m * (b * b + c * c) / 12, m * (a * a + c * c) / 12,
                           m * (a * a + b * b) / 12);
}

Mat3 cylinder_inertia(const GiNaC::ex& m, const GiNaC::ex& radius, const GiNaC::ex& length) {
  const GiNaC::ex side = m * (3 * radius * radius + length * length) / 12;
  return principal_inertia(side, side, m * radius * radius / 2);
}

Mat3 sphere_inertia(const GiNaC::ex& m, const GiNaC::ex& radius) {
  const GiNaC::ex i = GiNaC::numeric(2, 5) * m * radius * radius;
  return principal_inertia(i, i, i);
}

Mat3 parallel_axis(const Mat3& I, const GiNaC::ex& m, const Vec3& d) {
  const GiNaC::ex d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  Mat3 out;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) out[i][j] = I[i][j] + m * ((i == j ? d2 : 0) - d[i] * d[j]);
  return out;
}

namespace {

double value_of(const Model& model, const GiNaC::ex& e, const Body& body, const char* what) {
  GiNaC::exmap values;
  for (const auto& p : model.parameters) values[p.sym] = p.value;
  const GiNaC::ex v = e.subs(values).evalf();
  if (!GiNaC::is_a<GiNaC::numeric>(v) || !GiNaC::ex_to<GiNaC::numeric>(v).is_real()) {
    std::ostringstream os;
    os << e;
    throw ModelError(body.loc, fmt::format("the {} of body '{}' must be a number or an expression "
                                           "of parameters, got {}",
                                           what, body.name, os.str()));
  }
  return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
}

}  // namespace

// docs/theory.md §4.4: principal moments of a physical body are non-negative and satisfy the
// triangle inequality I₁ + I₂ ≥ I₃ (zero moments: thin rods, point-like bodies). A free body's
// ω equations J ω̇ = … need J invertible; a posed body turning about one body axis k only uses
// J_kk, so the planar form with every other entry zero is accepted too.
void check_body_inertia(const Model& model, const Body& body, std::optional<size_t> spin_axis) {
  const double m = value_of(model, body.mass, body, "mass");
  if (!(m > 0))
    throw ModelError(body.loc,
                     fmt::format("body '{}': expected a positive mass, got {}", body.name, m));
  Eigen::Matrix3d I;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) I(i, j) = value_of(model, body.inertia[i][j], body, "inertia");
  const double scale = I.cwiseAbs().maxCoeff();
  const double tol = 1e-12 * std::max(scale, 1e-300);
  if ((I - I.transpose()).cwiseAbs().maxCoeff() > tol)
    throw ModelError(body.loc,
                     fmt::format("body '{}': the inertia tensor is not symmetric", body.name));
  const Eigen::Vector3d p = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I).eigenvalues();
  const std::string moments = fmt::format("({:.6g}, {:.6g}, {:.6g})", p[0], p[1], p[2]);
  if (!(p[0] >= -tol))
    throw ModelError(body.loc, fmt::format("body '{}': non-physical inertia, principal moments {} "
                                           "must be non-negative",
                                           body.name, moments));
  if (body.free && !(p[0] > tol))
    throw ModelError(body.loc,
                     fmt::format("body '{}': a free body needs a positive-definite inertia (its "
                                 "angular velocity equations solve J ω̇ = …), got principal "
                                 "moments {}; pose the body by coordinates, or give it a "
                                 "thickness",
                                 body.name, moments));
  if (spin_axis) {
    const auto k = static_cast<int>(*spin_axis);
    Eigen::Matrix3d rest = I;
    rest(k, k) = 0;
    if (rest.cwiseAbs().maxCoeff() <= tol) return;  // planar: only J_kk enters T
  }
  if (p[0] + p[1] < p[2] - tol)
    throw ModelError(body.loc, fmt::format("body '{}': non-physical inertia, principal moments {} "
                                           "violate the triangle inequality I1 + I2 >= I3",
                                           body.name, moments));
}

}  // namespace lagrange
