#include "model/expression_parser.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>

#include "model/exact_numbers.hpp"
#include "model/expression_algebra.hpp"

namespace lagrange::model {

namespace {

/// Built-in functions: name → number of arguments.
const std::map<std::string, int>& builtin_arity() {
  static const std::map<std::string, int> table = {
      {"sin", 1},   {"cos", 1},   {"tan", 1},   {"asin", 1},  {"acos", 1},     {"atan", 1},
      {"atan2", 2}, {"sinh", 1},  {"cosh", 1},  {"tanh", 1},  {"exp", 1},      {"log", 1},
      {"sqrt", 1},  {"abs", 1},   {"dot", 2},   {"cross", 2}, {"norm", 1},     {"vel", 1},
      {"der", 1},   {"rot_x", 1}, {"rot_y", 1}, {"rot_z", 1}, {"transpose", 1}};
  return table;
}

/// " (did you mean 'log'?)" for names other languages give to built-in functions.
std::string hint(const std::string& name) {
  static const std::map<std::string, std::string> aliases = {
      {"ln", "log"},     {"arcsin", "asin"},         {"arccos", "acos"}, {"arctan", "atan"},
      {"pow", "a^b"},    {"power", "a^b"},           {"sqr", "x^2"},     {"fabs", "abs"},
      {"exp10", "10^x"}, {"log10", "log(x)/log(10)"}};
  auto it = aliases.find(name);
  return it == aliases.end() ? "" : fmt::format(" (did you mean '{}'?)", it->second);
}

/// An exact GiNaC number for a decimal literal (rational when reasonably sized), finite.
GiNaC::ex number_value(const Token& tok) {
  const std::string& s = tok.text;
  double d = std::strtod(s.c_str(), nullptr);
  if (!std::isfinite(d))
    throw ExprError{tok.offset, fmt::format("expected a finite number, got '{}'", clip(s))};
  if (d != 0 && std::fabs(d) < std::numeric_limits<double>::min())
    throw ExprError{tok.offset,
                    fmt::format("expected a number of magnitude 0 or at least {:g}, got '{}'",
                                std::numeric_limits<double>::min(), clip(s))};
  std::string digits;
  long exponent = 0;
  size_t i = 0;
  bool fraction = false;
  for (; i < s.size() && s[i] != 'e' && s[i] != 'E'; ++i) {
    if (s[i] == '.') {
      fraction = true;
    } else {
      digits += s[i];
      if (fraction) --exponent;
    }
  }
  // strtol saturates at LONG_MIN/MAX; clamp so that adding the fraction's digits cannot overflow
  // (a fuzz finding: '.1e-3209…'). |exponent| > 300 takes the double path below anyway.
  if (i < s.size())
    exponent += std::clamp(std::strtol(s.c_str() + i + 1, nullptr, 10), -100000L, 100000L);
  size_t nz = digits.find_first_not_of('0');
  digits = nz == std::string::npos ? "0" : digits.substr(nz);
  if (digits.size() > 40 || std::labs(exponent) > 300) return GiNaC::numeric(d);
  GiNaC::numeric n(digits.c_str());
  return n * GiNaC::numeric(10).power(GiNaC::numeric(exponent));
}

class Parser {
 public:
  Parser(const std::string& text, const ParseContext& ctx) : toks_(tokenize(text)), ctx_(ctx) {}

  Value parse() {
    Value v = expr();
    if (peek().kind != TokenKind::End)
      throw ExprError{peek().offset,
                      fmt::format("expected an operator or the end, got {}", show(peek()))};
    return v;
  }

 private:
  const Token& peek() const { return toks_[pos_]; }
  const Token& next() { return toks_[pos_++]; }
  bool at(const char* sym) const { return peek().kind == TokenKind::Symbol && peek().text == sym; }
  static std::string show(const Token& t) {
    return t.kind == TokenKind::End ? "the end of the expression"
                                    : fmt::format("'{}'", clip(t.text));
  }
  void expect(const char* sym) {
    if (!at(sym))
      throw ExprError{peek().offset, fmt::format("expected '{}', got {}", sym, show(peek()))};
    ++pos_;
  }

  /// Run a GiNaC operation, turning its exceptions (division by zero, log(0)) into ExprError.
  template <class F>
  static auto guarded(size_t offset, F&& f) -> decltype(f()) {
    try {
      return f();
    } catch (const ExprError&) {
      throw;
    } catch (const std::exception& e) {
      throw ExprError{offset, fmt::format("cannot evaluate this: {}", e.what())};
    }
  }

  /// f(x) for every component x of v: a scalar's one, a vector's three, a matrix's nine.
  template <class F>
  static void each_component(const Value& v, F&& f) {
    if (v.is_matrix) {
      for (const Vec3& row : v.mat)
        for (const GiNaC::ex& x : row) f(x);
    } else if (v.is_vector) {
      for (const GiNaC::ex& x : v.vec) f(x);
    } else {
      f(v.scalar);
    }
  }

  /// `v` after checking the numbers its operation folded (check_folded on every component).
  static Value folded(const Value& v, size_t offset) {
    each_component(v, [&](const GiNaC::ex& x) { check_folded(x, offset); });
    return v;
  }

  /// `folded(v)` after checking that a function or power of real operands stayed real; sums and
  /// products of real operands are real, so only these two check (check_real).
  static Value real(const Value& v, size_t offset) {
    each_component(v, [&](const GiNaC::ex& x) { check_real(x, offset); });
    return folded(v, offset);
  }

  Value expr() {
    Value lhs = term();
    while (at("+") || at("-")) {
      const Token& op = next();
      Value rhs = term();
      lhs = folded(add(lhs, rhs, op.text, op.offset), op.offset);
    }
    return lhs;
  }

  Value term() {
    Value lhs = unary();
    while (at("*") || at("/")) {
      const Token& op = next();
      if (op.text == "*" && at("*") && peek().offset == op.offset + 1)
        throw ExprError{op.offset,
                        "expected an operand after '*', got '**' (did you mean '^'? "
                        "powers are written a^b)"};
      Value rhs = unary();
      lhs = folded(op.text == "*" ? multiply(lhs, rhs, op.offset) : divide(lhs, rhs, op.offset),
                   op.offset);
    }
    return lhs;
  }

  Value unary() {
    if (++depth_ > ctx_.max_depth)
      throw ExprError{peek().offset, fmt::format("expected at most {} levels of nesting, got more",
                                                 ctx_.max_depth)};
    Value v;
    if (at("-") || at("+")) {
      const Token& op = next();
      v = unary();
      if (op.text == "-") v = negate(v);
    } else {
      v = power();
    }
    --depth_;
    return v;
  }

  Value power() {
    Value base = postfix();
    if (!at("^")) return base;
    const Token& op = next();
    Value exponent = unary();
    if (base.is_vector || exponent.is_vector || base.is_matrix || exponent.is_matrix)
      throw ExprError{op.offset, fmt::format("expected scalar ^ scalar, got {} ^ {}",
                                             kind_name(base), kind_name(exponent))};
    check_power(base.scalar, exponent.scalar, op.offset);
    // number ^ number where GiNaC evaluates the result anyway: do it on the numbers, so that a
    // CLN exception (underflow, overflow) does not leak pow()'s half-built node (fuzz finding).
    if (GiNaC::is_a<GiNaC::numeric>(base.scalar) && GiNaC::is_a<GiNaC::numeric>(exponent.scalar)) {
      const auto& b = GiNaC::ex_to<GiNaC::numeric>(base.scalar);
      const auto& e = GiNaC::ex_to<GiNaC::numeric>(exponent.scalar);
      if (e.is_integer() || !b.is_rational())
        return real(Value::of(guarded(op.offset, [&] { return GiNaC::ex(b.power(e)); })),
                    op.offset);
    }
    return real(
        Value::of(guarded(op.offset,
                          [&] { return GiNaC::ex(GiNaC::pow(base.scalar, exponent.scalar)); })),
        op.offset);
  }

  Value postfix() {
    Value v = primary();
    while (at(".")) {
      const Token& dot = next();
      const Token& comp = peek();
      if (comp.kind != TokenKind::Name ||
          (comp.text != "x" && comp.text != "y" && comp.text != "z"))
        throw ExprError{comp.offset,
                        fmt::format("expected x, y or z after '.', got {}", show(comp))};
      ++pos_;
      if (!v.is_vector)
        throw ExprError{dot.offset, fmt::format("expected a vector before '.{}', got {}", comp.text,
                                                kind_name(v))};
      v = Value::of(v.vec[static_cast<size_t>(comp.text[0] - 'x')]);
    }
    return v;
  }

  Value primary() {
    const Token& tok = peek();
    if (tok.kind == TokenKind::Number) {
      ++pos_;
      return Value::of(number_value(tok));
    }
    if (tok.kind == TokenKind::Name) {
      ++pos_;
      if (at("(")) return call(tok);
      if (builtin_arity().count(tok.text))
        throw ExprError{peek().offset, fmt::format("expected '(' after function '{}', got {}",
                                                   tok.text, show(peek()))};
      if (tok.text == "pi") return Value::of(GiNaC::Pi);
      if (std::optional<Value> member = dotted(tok)) return *member;
      std::optional<Value> v = ctx_.resolve ? ctx_.resolve(tok.text, tok.offset) : std::nullopt;
      if (!v) throw ExprError{tok.offset, fmt::format("unknown name '{}'", clip(tok.text))};
      return *v;
    }
    if (at("(")) {
      ++pos_;
      Value v = expr();
      expect(")");
      return v;
    }
    if (at("[")) return vector_literal();
    throw ExprError{tok.offset,
                    fmt::format("expected a number, a name, '(' or '[', got {}", show(tok))};
  }

  /// `a.b` as one name (a body's r, R or point) when the resolver knows it.
  std::optional<Value> dotted(const Token& tok) {
    if (!at(".") || toks_[pos_ + 1].kind != TokenKind::Name || !ctx_.resolve) return std::nullopt;
    std::optional<Value> v = ctx_.resolve(tok.text + "." + toks_[pos_ + 1].text, tok.offset);
    if (v) pos_ += 2;
    return v;
  }

  Value vector_literal() {
    const Token& open = next();
    std::vector<Value> items;
    if (!at("]")) {
      items.push_back(expr());
      while (at(",")) {
        ++pos_;
        items.push_back(expr());
      }
    }
    expect("]");
    if (items.size() != 3)
      throw ExprError{open.offset,
                      fmt::format("expected a vector of 3 components, got {}", items.size())};
    if (items[0].is_vector && items[1].is_vector && items[2].is_vector)
      return Value::of(Mat3{items[0].vec, items[1].vec, items[2].vec});
    Vec3 out;
    for (size_t i = 0; i < 3; ++i) {
      if (items[i].is_matrix)
        throw ExprError{open.offset,
                        fmt::format("expected scalar components or three row vectors, got a "
                                    "matrix as component {}",
                                    i + 1)};
      if (items[i].is_vector)
        throw ExprError{
            open.offset,
            fmt::format("expected scalar vector components, got a vector as component {}", i + 1)};
      out[i] = items[i].scalar;
    }
    return Value::of(out);
  }

  Value call(const Token& name) {
    auto it = builtin_arity().find(name.text);
    if (it == builtin_arity().end())
      throw ExprError{name.offset,
                      fmt::format("unknown function '{}'{}", clip(name.text), hint(name.text))};
    expect("(");
    std::vector<Value> args{expr()};
    while (at(",")) {
      ++pos_;
      args.push_back(expr());
    }
    expect(")");
    if (static_cast<int>(args.size()) != it->second)
      throw ExprError{name.offset,
                      fmt::format("expected {} argument{} for '{}', got {}{}", it->second,
                                  it->second == 1 ? "" : "s", name.text, args.size(),
                                  name.text == "dot" && args.size() == 1
                                      ? " (dot(a, b) is the scalar product; a time derivative "
                                        "is written der(x))"
                                      : "")};
    return real(guarded(name.offset, [&] { return apply(name, args); }), name.offset);
  }

  /// Argument `index` of `f` must be a vector (`vector`) or a scalar (otherwise).
  void require(const Token& f, const Value& v, bool vector, size_t index) const {
    if (v.is_vector == vector && !v.is_matrix) return;
    throw ExprError{f.offset,
                    fmt::format("expected {} as argument {} of '{}', got {}",
                                vector ? "a vector" : "a scalar", index + 1, f.text, kind_name(v))};
  }

  GiNaC::ex derivative(const Token& f, const GiNaC::ex& e) const {
    if (!ctx_.time_derivative)
      throw ExprError{f.offset, fmt::format("expected no time derivative here, got '{}'", f.text)};
    try {
      return ctx_.time_derivative(e);
    } catch (const std::logic_error&) {
      throw ExprError{f.offset,
                      fmt::format("expected at most second time derivatives, got '{}' of an "
                                  "acceleration or of an input's second derivative",
                                  f.text)};
    }
  }

  Value apply(const Token& f, const std::vector<Value>& a) const {
    const std::string& n = f.text;
    if (n == "dot" || n == "cross") {
      require(f, a[0], true, 0);
      require(f, a[1], true, 1);
      const Vec3 &x = a[0].vec, &y = a[1].vec;
      if (n == "dot") return Value::of(x[0] * y[0] + x[1] * y[1] + x[2] * y[2]);
      return Value::of(
          Vec3{x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]});
    }
    if (n == "norm") {
      require(f, a[0], true, 0);
      const Vec3& x = a[0].vec;
      return Value::of(GiNaC::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]));
    }
    if (n == "vel") {
      require(f, a[0], true, 0);
      Vec3 d;
      for (size_t i = 0; i < 3; ++i) d[i] = derivative(f, a[0].vec[i]);
      return Value::of(d);
    }
    if (n == "transpose") {
      if (!a[0].is_matrix)
        throw ExprError{f.offset, fmt::format("expected a matrix as argument 1 of 'transpose', "
                                              "got {}",
                                              kind_name(a[0]))};
      return Value::of(transpose(a[0].mat));
    }
    for (size_t i = 0; i < a.size(); ++i) require(f, a[i], false, i);
    const GiNaC::ex& x = a[0].scalar;
    if (n.rfind("rot_", 0) == 0) return Value::of(axis_rotation(size_t(n[4] - 'x'), x));
    if (n == "der") return Value::of(derivative(f, x));
    if (n == "atan2") return Value::of(GiNaC::atan2(x, a[1].scalar));
    if (n == "sin") return Value::of(GiNaC::sin(x));
    if (n == "cos") return Value::of(GiNaC::cos(x));
    if (n == "tan") return Value::of(GiNaC::tan(x));
    if (n == "asin") return Value::of(GiNaC::asin(x));
    if (n == "acos") return Value::of(GiNaC::acos(x));
    if (n == "atan") return Value::of(GiNaC::atan(x));
    if (n == "sinh") return Value::of(GiNaC::sinh(x));
    if (n == "cosh") return Value::of(GiNaC::cosh(x));
    if (n == "tanh") return Value::of(GiNaC::tanh(x));
    if (n == "exp") return Value::of(GiNaC::exp(x));
    if (n == "log") return Value::of(GiNaC::log(x));
    if (n == "sqrt") return Value::of(GiNaC::sqrt(x));
    return Value::of(real_abs(x));  // the only remaining one-argument function
  }

  std::vector<Token> toks_;
  const ParseContext& ctx_;
  size_t pos_ = 0;
  int depth_ = 0;
};

}  // namespace

Value parse_expression(const std::string& text, const ParseContext& ctx) {
  return Parser(text, ctx).parse();
}

bool is_builtin_function(const std::string& name) {
  return builtin_arity().count(name) != 0;
}

std::vector<std::pair<std::string, size_t>> referenced_names(const std::string& text) {
  std::vector<std::pair<std::string, size_t>> out;
  std::vector<Token> toks;
  try {
    toks = tokenize(text);
  } catch (const ExprError&) {
    return out;
  }
  for (size_t i = 0; i < toks.size(); ++i) {
    if (toks[i].kind != TokenKind::Name) continue;
    bool component = i > 0 && toks[i - 1].kind == TokenKind::Symbol && toks[i - 1].text == ".";
    bool function = toks[i + 1].kind == TokenKind::Symbol && toks[i + 1].text == "(";
    if (!component && !function) out.emplace_back(toks[i].text, toks[i].offset);
  }
  return out;
}

}  // namespace lagrange::model
