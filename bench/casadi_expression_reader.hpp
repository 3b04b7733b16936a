#pragma once
// The expression reader the CasADi peers share: lagrange's printed equations into CasADi's SX
// (bench/optimal_control_casadi_panda.cpp, bench/optimal_control_casadi_kite.cpp).
#include <casadi/casadi.hpp>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>
#include <stdexcept>
#include <string>

namespace casadi_peer {

using casadi::SX;

/// `lagrange derive --format json`'s expressions (GiNaC's printing, or the tape's text of
/// src/compile/tape_emit_text.cpp for a large model): numbers, names (a winch's `drum.reeled_out`
/// included), + − * / ^, unary minus, parentheses, one-argument functions and atan2(a, b), read
/// into SX by recursive descent.
class ExpressionReader {
 public:
  explicit ExpressionReader(std::map<std::string, SX>& names) : names_(names) {}

  SX read(const std::string& text) {
    s_ = &text;
    at_ = 0;
    SX e = sum();
    skip();
    if (at_ != text.size()) fail("unexpected text");
    return e;
  }

 private:
  void skip() {
    while (at_ < s_->size() && std::isspace(static_cast<unsigned char>((*s_)[at_]))) ++at_;
  }
  bool eat(char c) {
    skip();
    if (at_ < s_->size() && (*s_)[at_] == c) {
      ++at_;
      return true;
    }
    return false;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(what + " at column " + std::to_string(at_ + 1) + " of '" +
                             s_->substr(0, 200) + "'");
  }
  SX sum() {
    SX e = product();
    for (;;) {
      if (eat('+'))
        e += product();
      else if (eat('-'))
        e -= product();
      else
        return e;
    }
  }
  SX product() {
    SX e = unary();
    for (;;) {
      if (eat('*'))
        e *= unary();
      else if (eat('/'))
        e /= unary();
      else
        return e;
    }
  }
  SX unary() { return eat('-') ? SX(-unary()) : power(); }
  SX power() {
    SX base = primary();
    if (!eat('^')) return base;
    skip();
    const size_t mark = at_;
    char* end = nullptr;
    const double n = std::strtod(s_->c_str() + at_, &end);
    const bool integer = end != s_->c_str() + at_ && n == std::floor(n) && (*s_)[at_] != '(';
    if (integer) {
      at_ = static_cast<size_t>(end - s_->c_str());
      return n == 2 ? SX::sq(base) : SX::constpow(base, n);
    }
    at_ = mark;
    return pow(base, unary());
  }
  SX primary() {
    skip();
    if (eat('(')) {
      SX e = sum();
      if (!eat(')')) fail("expected ')'");
      return e;
    }
    if (at_ < s_->size() &&
        (std::isdigit(static_cast<unsigned char>((*s_)[at_])) || (*s_)[at_] == '.')) {
      char* end = nullptr;
      const double v = std::strtod(s_->c_str() + at_, &end);
      at_ = static_cast<size_t>(end - s_->c_str());
      return v;
    }
    const size_t from = at_;
    while (at_ < s_->size() && (std::isalnum(static_cast<unsigned char>((*s_)[at_])) ||
                                (*s_)[at_] == '_' || (*s_)[at_] == '.'))
      ++at_;
    if (at_ == from) fail("expected a number, a name or '('");
    const std::string name = s_->substr(from, at_ - from);
    if (!eat('(')) {
      const auto found = names_.find(name);
      if (found == names_.end()) fail("unknown name '" + name + "'");
      return found->second;
    }
    const SX a = sum();
    if (name == "atan2") {
      if (!eat(',')) fail("expected ',' in atan2");
      const SX b = sum();
      if (!eat(')')) fail("expected ')'");
      return atan2(a, b);
    }
    if (!eat(')')) fail("expected ')'");
    // CasADi's operation codes for the tape's one-argument functions (casadi/core/calculus.hpp).
    static const std::map<std::string, casadi_int> functions{
        {"sin", casadi::OP_SIN},   {"cos", casadi::OP_COS},   {"tan", casadi::OP_TAN},
        {"asin", casadi::OP_ASIN}, {"acos", casadi::OP_ACOS}, {"atan", casadi::OP_ATAN},
        {"sinh", casadi::OP_SINH}, {"cosh", casadi::OP_COSH}, {"tanh", casadi::OP_TANH},
        {"exp", casadi::OP_EXP},   {"log", casadi::OP_LOG},   {"sqrt", casadi::OP_SQRT},
        {"fabs", casadi::OP_FABS}, {"abs", casadi::OP_FABS}};
    const auto f = functions.find(name);
    if (f == functions.end()) fail("unknown function '" + name + "'");
    return SX::unary(f->second, a);
  }

  std::map<std::string, SX>& names_;
  const std::string* s_ = nullptr;
  size_t at_ = 0;
};

}  // namespace casadi_peer
