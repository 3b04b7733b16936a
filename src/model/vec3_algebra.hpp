#pragma once
// 3-vector and 3×3-matrix products of expressions, shared by the elements' joint frames
// (docs/theory.md §4.8), the rigid-body terms (§4.4), the recursive formulation (§4.9), the
// tethers (§4.5, §4.10) and the wind (§4.5); and the branch-free max and min of two scalars.

#include "lagrange/model.hpp"

namespace lagrange::model {

/// Every component identically zero (as GiNaC's is_zero: no simplification).
inline bool is_zero(const Vec3& v) {
  return v[0].is_zero() && v[1].is_zero() && v[2].is_zero();
}

/// a + b.
inline Vec3 add(const Vec3& a, const Vec3& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}

/// a − b.
inline Vec3 sub(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

/// s a.
inline Vec3 scale(const GiNaC::ex& s, const Vec3& a) {
  return {s * a[0], s * a[1], s * a[2]};
}

/// a · b.
inline GiNaC::ex dot3(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// max(a, b) = (a + b + |a − b|)/2, written with abs, which the tape and the C exporter evaluate
/// without branches.
inline GiNaC::ex max_of(const GiNaC::ex& a, const GiNaC::ex& b) {
  return (a + b + GiNaC::abs(a - b)) / 2;
}

/// min(a, b) = (a + b − |a − b|)/2, as max_of.
inline GiNaC::ex min_of(const GiNaC::ex& a, const GiNaC::ex& b) {
  return (a + b - GiNaC::abs(a - b)) / 2;
}

/// a × b.
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

/// A x.
inline Vec3 mat_vec(const Mat3& A, const Vec3& x) {
  Vec3 y;
  for (size_t i = 0; i < 3; ++i) y[i] = A[i][0] * x[0] + A[i][1] * x[1] + A[i][2] * x[2];
  return y;
}

/// Aᵀ x.
inline Vec3 mat_t_vec(const Mat3& A, const Vec3& x) {
  Vec3 y;
  for (size_t i = 0; i < 3; ++i) y[i] = A[0][i] * x[0] + A[1][i] * x[1] + A[2][i] * x[2];
  return y;
}

/// X Y.
inline Mat3 mat_mul(const Mat3& X, const Mat3& Y) {
  Mat3 Z;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      Z[i][j] = X[i][0] * Y[0][j] + X[i][1] * Y[1][j] + X[i][2] * Y[2][j];
  return Z;
}

}  // namespace lagrange::model
