#include <fmt/format.h>

#include <cmath>

#include "lagrange/rigid_body.hpp"
#include "model/model_reader.hpp"

namespace lagrange::model {

namespace {
/// A given rotation matrix must satisfy ‖RᵀR − 1‖_F below this (and det R > 0).
constexpr double kOrthonormalTolerance = 1e-9;
}  // namespace

std::array<double, 3> ModelReader::numeric_vector(const YAML::Node& node,
                                                  const std::string& what) const {
  const Vec3 v = vector_expr(node, kParams, what);
  std::array<double, 3> out{};
  for (size_t i = 0; i < 3; ++i) {
    const std::optional<double> x = evaluate(v[i]);
    if (!x || !std::isfinite(*x))
      fail(node.IsSequence() ? node[i] : node,
           fmt::format("expected a finite real number for component {} of {}", i + 1, what));
    out[i] = *x;
  }
  return out;
}

// docs/theory.md §4.4: q₀ ⊃ r₀, R₀ (row-major); v₀ ⊃ ṙ₀ (world frame) and ω₀ (body frame).
void ModelReader::read_free_initial(Body& body, const YAML::Node& node) {
  const std::string what = fmt::format("the initial state of body '{}'", body.name);
  check_keys(node, {"position", "orientation", "velocity", "omega"}, what);
  if (node["position"])
    body.r0 = numeric_vector(node["position"], "initial position of body '" + body.name + "'");
  if (node["orientation"]) body.R0 = read_orientation(body, node["orientation"]);
  if (node["velocity"])
    body.v0 = numeric_vector(node["velocity"], "initial velocity of body '" + body.name + "'");
  if (node["omega"])
    body.w0 = numeric_vector(node["omega"],
                             "initial angular velocity (body frame) of body '" + body.name + "'");
}

// One of: matrix (checked orthonormal), axis_angle {axis, angle}, euler [roll, pitch, yaw]
// (R = R_z(yaw) R_y(pitch) R_x(roll)), quaternion [w, x, y, z] (normalised).
Rotation ModelReader::read_orientation(const Body& body, const YAML::Node& node) {
  const std::string what = fmt::format("the initial orientation of body '{}'", body.name);
  check_keys(node, {"matrix", "axis_angle", "euler", "quaternion"}, what);
  if (node.size() != 1)
    fail(node, fmt::format("expected one of matrix, axis_angle, euler, quaternion in {}, got {}",
                           what, node.size()));
  if (const YAML::Node m = node["matrix"]) {
    const Mat3 e = matrix_expr(m, kParams, "orientation matrix of body '" + body.name + "'");
    Rotation R{};
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) {
        const std::optional<double> x = evaluate(e[i][j]);
        if (!x || !std::isfinite(*x))
          fail(m, fmt::format("expected finite real numbers in the orientation matrix of body "
                              "'{}'",
                              body.name));
        R[3 * i + j] = *x;
      }
    const double err = orthonormality_error(R.data());
    const double det = determinant(R.data());
    if (!(err < kOrthonormalTolerance) || !(det > 0))
      fail(m, fmt::format("expected a rotation matrix (RᵀR = 1 to {:g}, det R = +1) for body "
                          "'{}', got ‖RᵀR − 1‖ = {:.3g}, det R = {:.6g} (give more digits, or "
                          "use axis_angle, euler or quaternion)",
                          kOrthonormalTolerance, body.name, err, det));
    return R;
  }
  if (const YAML::Node aa = node["axis_angle"]) {
    check_keys(aa, {"axis", "angle"}, "the axis_angle of body '" + body.name + "'");
    if (!aa["axis"] || !aa["angle"])
      fail(aa, fmt::format("expected 'axis' and 'angle' in the axis_angle of body '{}', got only "
                           "one",
                           body.name));
    const auto axis = numeric_vector(aa["axis"], "rotation axis of body '" + body.name + "'");
    if (axis[0] == 0 && axis[1] == 0 && axis[2] == 0)
      fail(aa["axis"], fmt::format("expected a non-zero rotation axis for body '{}', got [0, 0, 0]",
                                   body.name));
    return rotation_from_axis_angle(
        axis, number(aa["angle"], kParams, "rotation angle of body '" + body.name + "'"));
  }
  if (const YAML::Node eu = node["euler"]) {
    const auto a =
        numeric_vector(eu, "Euler angles [roll, pitch, yaw] of body '" + body.name + "'");
    return rotation_from_euler(a[0], a[1], a[2]);
  }
  const YAML::Node qn = node["quaternion"];
  if (!qn.IsSequence() || qn.size() != 4)
    fail(qn, fmt::format("expected a quaternion [w, x, y, z] for body '{}', got {}", body.name,
                         qn.IsSequence() ? fmt::format("{} numbers", qn.size()) : describe(qn)));
  std::array<double, 4> q{};
  for (size_t i = 0; i < 4; ++i)
    q[i] = number(qn[i], kParams,
                  fmt::format("quaternion component {} of body '{}'", i + 1, body.name));
  if (q[0] == 0 && q[1] == 0 && q[2] == 0 && q[3] == 0)
    fail(qn,
         fmt::format("expected a non-zero quaternion for body '{}', got [0, 0, 0, 0]", body.name));
  return rotation_from_quaternion(q);
}

}  // namespace lagrange::model
