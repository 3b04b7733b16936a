// Rotations of joint frames (docs/theory.md §4.8): URDF's roll-pitch-yaw and axis-angle, exact.

#include "elements/links.hpp"
#include "model/expression_algebra.hpp"

namespace lagrange::elements {

// URDF: R = R_z(yaw) R_y(pitch) R_x(roll); zero angles leave their factor out.
Mat3 rpy_rotation(const Vec3& rpy) {
  Mat3 r{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};
  for (size_t axis : {2, 1, 0})
    if (!rpy[axis].is_zero()) r = mat_mul(r, model::axis_rotation(axis, rpy[axis]));
  return r;
}

// R = cos θ 1 + sin θ [k]× + (1 − cos θ) k kᵀ; a coordinate axis ±e_i gives rot_i(±θ).
Mat3 axis_angle_rotation(const Vec3& k, const GiNaC::ex& angle) {
  for (size_t i = 0; i < 3; ++i) {
    const size_t j = (i + 1) % 3, l = (i + 2) % 3;
    if (k[j].is_zero() && k[l].is_zero() && (k[i] - 1).is_zero())
      return model::axis_rotation(i, angle);
    if (k[j].is_zero() && k[l].is_zero() && (k[i] + 1).is_zero())
      return model::axis_rotation(i, -angle);
  }
  const GiNaC::ex c = GiNaC::cos(angle), s = GiNaC::sin(angle);
  const Mat3 cross{Vec3{0, -k[2], k[1]}, Vec3{k[2], 0, -k[0]}, Vec3{-k[1], k[0], 0}};
  Mat3 r;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      r[i][j] = (i == j ? c : GiNaC::ex(0)) + s * cross[i][j] + (1 - c) * k[i] * k[j];
  return r;
}

}  // namespace lagrange::elements
