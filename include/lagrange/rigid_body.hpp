#pragma once
// Rigid-body helpers (docs/theory.md §4.4, §4.8): inertia of shapes, the parallel-axis theorem,
// physical-inertia checks and initial orientations.

#include <array>
#include <optional>

#include "lagrange/model.hpp"

namespace lagrange {

/// Solid box with edges a, b, c along the body axes: I_xx = m(b² + c²)/12 and cyclic.
Mat3 box_inertia(const GiNaC::ex& m, const GiNaC::ex& a, const GiNaC::ex& b, const GiNaC::ex& c);
/// Solid cylinder along the body z axis: I_zz = m r²/2, I_xx = I_yy = m(3r² + h²)/12.
Mat3 cylinder_inertia(const GiNaC::ex& m, const GiNaC::ex& radius, const GiNaC::ex& length);
/// Solid sphere: I = (2/5) m r² on the diagonal.
Mat3 sphere_inertia(const GiNaC::ex& m, const GiNaC::ex& radius);
/// Diagonal tensor from principal moments.
Mat3 principal_inertia(const GiNaC::ex& ixx, const GiNaC::ex& iyy, const GiNaC::ex& izz);
/// Parallel-axis theorem: the tensor about a point at offset d from the centre of mass,
/// I + m(|d|² 1 − d dᵀ).
Mat3 parallel_axis(const Mat3& inertia_com, const GiNaC::ex& m, const Vec3& d);

/// Throws ModelError at the body's location, naming it, when its mass is not positive or its
/// inertia (at the parameters' values) is not symmetric, has a negative principal moment,
/// violates the triangle inequality I₁ + I₂ ≥ I₃, or is singular for a free body. A posed body
/// that turns about body axis `spin_axis` only may give J_kk alone (planar `[0, 0, Izz]`).
void check_body_inertia(const Model& model, const Body& body,
                        std::optional<size_t> spin_axis = std::nullopt);

/// Row-major rotation matrices (body → world) from the usual descriptions.
using Rotation = std::array<double, 9>;
/// Rotation by `angle` about `axis` (normalised here; a zero axis is std::invalid_argument).
Rotation rotation_from_axis_angle(const std::array<double, 3>& axis, double angle);
/// R = R_z(yaw) R_y(pitch) R_x(roll) (aerospace Z-Y-X Euler angles).
Rotation rotation_from_euler(double roll, double pitch, double yaw);
/// Unit quaternion (w, x, y, z), normalised here; a zero quaternion is std::invalid_argument.
Rotation rotation_from_quaternion(const std::array<double, 4>& q);
/// ‖RᵀR − 1‖_F, the orthonormality error of a row-major 3×3 matrix.
double orthonormality_error(const double* R);
/// det R of a row-major 3×3 matrix (+1 for a rotation, −1 for a reflection).
double determinant(const double* R);

}  // namespace lagrange
