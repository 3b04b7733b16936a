#pragma once
// Recursive-descent parser of model expressions into GiNaC (docs/model-language.md).
//
//   expr    := term (('+' | '-') term)*
//   term    := unary (('*' | '/') unary)*
//   unary   := ('-' | '+') unary | power
//   power   := postfix ('^' unary)?                       right-associative, above unary minus
//   postfix := primary ('.' ('x' | 'y' | 'z'))*
//   primary := number | name ['.' name] | name '(' expr (',' expr)* ')' | '(' expr ')'
//            | '[' expr ',' expr ',' expr ']'          a vector; a matrix when all three are rows

#include <functional>
#include <optional>
#include <string>

#include "lagrange/model.hpp"
#include "model/expression_lexer.hpp"

namespace lagrange::model {

/// The value of an expression: a scalar, a 3-vector or a 3×3 matrix (at most one flag set).
struct Value {
  bool is_vector = false;
  GiNaC::ex scalar;
  Vec3 vec;
  bool is_matrix = false;
  Mat3 mat;

  static Value of(const GiNaC::ex& s) { return Value{false, s, {}, false, {}}; }
  static Value of(const Vec3& v) { return Value{true, 0, v, false, {}}; }
  static Value of(const Mat3& m) { return Value{false, 0, {}, true, m}; }
};

/// Looks up a name at an offset: a value, or nullopt when unknown. May throw ExprError itself.
/// For `a.b` (a name, a dot, a name) the parser first asks for "a.b" (a body's `r`, `R` or
/// point); when that is unknown it reads `a` followed by the component `.b`.
using NameResolver = std::function<std::optional<Value>(const std::string& name, size_t offset)>;

/// Parser settings; `time_derivative` implements der() and vel() (nullptr: those are errors).
struct ParseContext {
  NameResolver resolve;
  std::function<GiNaC::ex(const GiNaC::ex&)> time_derivative;
  int max_depth = 500;
};

/// Parse `text` into a value. Throws ExprError (offset inside `text`) on any mistake.
Value parse_expression(const std::string& text, const ParseContext& ctx);

/// True for the names of built-in functions (sin, dot, vel, …), which user names may not shadow.
bool is_builtin_function(const std::string& name);

/// Names referenced in `text` as values (not functions, not components), with offsets;
/// empty if the text does not tokenize.
std::vector<std::pair<std::string, size_t>> referenced_names(const std::string& text);

}  // namespace lagrange::model
