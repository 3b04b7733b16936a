#pragma once
// Arithmetic on expression values — scalars, 3-vectors and 3×3 matrices — with the type rules
// of docs/model-language.md ("Expressions"); mistakes are ExprError at the operator's offset.

#include <string>

#include "model/expression_parser.hpp"

namespace lagrange::model {

/// "a scalar", "a vector" or "a matrix", for messages.
const char* kind_name(const Value& v);

/// −v for any kind.
Value negate(const Value& v);
/// l + r or l − r (`op` is "+" or "-"): both of the same kind.
Value add(const Value& l, const Value& r, const std::string& op, size_t offset);
/// l · r: scalar·anything, anything·scalar, matrix·vector, matrix·matrix.
Value multiply(const Value& l, const Value& r, size_t offset);
/// l / r for a scalar r (division by a literal zero is an error).
Value divide(const Value& l, const Value& r, size_t offset);

/// Mᵀ.
Mat3 transpose(const Mat3& m);
/// |x| for a real-valued model expression: a power of a positive number is its own absolute
/// value, as is exp(y), |b^e| = |b|^e for a real number e, and |a b| = |a| |b|. GiNaC's abs()
/// treats symbols as complex and, for such a power, expands real parts whose size doubles with each
/// level of a power tower (a fuzz finding).
GiNaC::ex real_abs(const GiNaC::ex& x);

/// Rotation by `angle` about body axis 0 (x), 1 (y) or 2 (z): rot_x, rot_y, rot_z.
Mat3 axis_rotation(size_t axis, const GiNaC::ex& angle);

}  // namespace lagrange::model
