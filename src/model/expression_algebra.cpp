#include "model/expression_algebra.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace lagrange::model {

namespace {

Value scale(const Value& v, const GiNaC::ex& s) {
  if (v.is_matrix) {
    Mat3 out;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) out[i][j] = v.mat[i][j] * s;
    return Value::of(out);
  }
  if (v.is_vector) return Value::of(Vec3{v.vec[0] * s, v.vec[1] * s, v.vec[2] * s});
  return Value::of(v.scalar * s);
}

bool is_scalar(const Value& v) {
  return !v.is_vector && !v.is_matrix;
}

}  // namespace

const char* kind_name(const Value& v) {
  return v.is_matrix ? "a matrix" : v.is_vector ? "a vector" : "a scalar";
}

Value negate(const Value& v) {
  return scale(v, -1);
}

Value add(const Value& l, const Value& r, const std::string& op, size_t offset) {
  if (l.is_vector != r.is_vector || l.is_matrix != r.is_matrix)
    throw ExprError{offset, fmt::format("expected two values of the same kind around '{}', got {} "
                                        "{} {}",
                                        op, kind_name(l), op, kind_name(r))};
  const GiNaC::ex sign = op == "+" ? 1 : -1;
  if (l.is_matrix) {
    Mat3 out;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) out[i][j] = l.mat[i][j] + sign * r.mat[i][j];
    return Value::of(out);
  }
  if (l.is_vector) {
    Vec3 out;
    for (size_t i = 0; i < 3; ++i) out[i] = l.vec[i] + sign * r.vec[i];
    return Value::of(out);
  }
  return Value::of(l.scalar + sign * r.scalar);
}

// M v and A B with the row-major convention of Mat3 (rows are Vec3).
Value multiply(const Value& l, const Value& r, size_t offset) {
  if (is_scalar(l)) return scale(r, l.scalar);
  if (is_scalar(r)) return scale(l, r.scalar);
  if (l.is_vector && r.is_vector)
    throw ExprError{
        offset, "expected at most one vector around '*', got two vectors (use dot() or cross())"};
  if (l.is_vector)
    throw ExprError{offset,
                    "expected a matrix times a vector, got a vector * a matrix (write "
                    "transpose(M)*v for the row vector vᵀM)"};
  if (r.is_vector) {
    Vec3 out;
    for (size_t i = 0; i < 3; ++i)
      out[i] = l.mat[i][0] * r.vec[0] + l.mat[i][1] * r.vec[1] + l.mat[i][2] * r.vec[2];
    return Value::of(out);
  }
  Mat3 out;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      out[i][j] = l.mat[i][0] * r.mat[0][j] + l.mat[i][1] * r.mat[1][j] + l.mat[i][2] * r.mat[2][j];
  return Value::of(out);
}

Value divide(const Value& l, const Value& r, size_t offset) {
  if (!is_scalar(r))
    throw ExprError{offset, fmt::format("expected a scalar divisor after '/', got {} / {}",
                                        kind_name(l), kind_name(r))};
  if (r.scalar.is_zero()) throw ExprError{offset, "cannot evaluate this: division by zero"};
  try {
    return scale(l, GiNaC::pow(r.scalar, -1));
  } catch (const std::exception& e) {
    throw ExprError{offset, fmt::format("cannot evaluate this: {}", e.what())};
  }
}

Mat3 transpose(const Mat3& m) {
  Mat3 out;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) out[i][j] = m[j][i];
  return out;
}

GiNaC::ex real_abs(const GiNaC::ex& x) {
  if (GiNaC::is_a<GiNaC::power>(x) && GiNaC::is_a<GiNaC::numeric>(x.op(0)) &&
      GiNaC::ex_to<GiNaC::numeric>(x.op(0)).is_positive())
    return x;
  // exp of a real argument is positive; GiNaC's abs() of an exp tower doubles per level too.
  if (GiNaC::is_the_function<GiNaC::exp_SERIAL>(x)) return x;
  // |b^e| = |b|^e for a real exponent: answered here, since GiNaC's abs() of a power of a
  // power asks whether every level is positive, twice per level (issue 25 item 4).
  if (GiNaC::is_a<GiNaC::power>(x) && GiNaC::is_a<GiNaC::numeric>(x.op(1)) &&
      GiNaC::ex_to<GiNaC::numeric>(x.op(1)).is_real())
    return GiNaC::pow(real_abs(x.op(0)), x.op(1));
  if (GiNaC::is_a<GiNaC::mul>(x)) {
    GiNaC::exvector factors;
    for (size_t i = 0; i < x.nops(); ++i) factors.push_back(real_abs(x.op(i)));
    return GiNaC::mul(factors);
  }
  return GiNaC::abs(x);
}

// rot_x(a) = [[1, 0, 0], [0, cos a, −sin a], [0, sin a, cos a]] and cyclic.
Mat3 axis_rotation(size_t axis, const GiNaC::ex& angle) {
  const size_t i = (axis + 1) % 3, j = (axis + 2) % 3;
  Mat3 m{Vec3{0, 0, 0}, Vec3{0, 0, 0}, Vec3{0, 0, 0}};
  m[axis][axis] = 1;
  m[i][i] = GiNaC::cos(angle);
  m[j][j] = GiNaC::cos(angle);
  m[i][j] = -GiNaC::sin(angle);
  m[j][i] = GiNaC::sin(angle);
  return m;
}

}  // namespace lagrange::model
