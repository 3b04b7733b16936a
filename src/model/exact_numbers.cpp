#include "model/exact_numbers.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "model/expression_lexer.hpp"

namespace lagrange::model {

namespace {

/// Decimal digits of the larger of numerator and denominator of an exact rational (0 otherwise).
double digits_of(const GiNaC::numeric& n) {
  if (!n.is_rational()) return 0.0;
  return std::max(n.numer().int_length(), n.denom().int_length()) * std::log10(2.0);
}

/// The digits of the largest exact number GiNaC builds when it raises `e` to a numeric power p,
/// per unit of |p|: a number, and numbers inside products and powers of numbers, are raised
/// with it ((2x)^p = 2^p x^p, (3^(1/2))^p = 3^(p/2)); sums and functions are not expanded.
double digits_per_unit_power(const GiNaC::ex& e) {
  if (GiNaC::is_a<GiNaC::numeric>(e)) return digits_of(GiNaC::ex_to<GiNaC::numeric>(e));
  if (GiNaC::is_a<GiNaC::mul>(e)) {
    double most = 0.0;
    for (size_t i = 0; i < e.nops(); ++i) most = std::max(most, digits_per_unit_power(e.op(i)));
    return most;
  }
  if (GiNaC::is_a<GiNaC::power>(e) && GiNaC::is_a<GiNaC::numeric>(e.op(1))) {
    const auto& p = GiNaC::ex_to<GiNaC::numeric>(e.op(1));
    if (!p.is_real()) return 0.0;
    return digits_per_unit_power(e.op(0)) * std::min(GiNaC::abs(p).to_double(), 1e300);
  }
  return 0.0;
}

/// Height of the tallest tower of powers with a non-numeric exponent in `e` (x^y: 1,
/// 9^9^x: 2; numbers and symbols: 0). Visits at most `budget` nodes (shared subexpressions
/// are visited again), answering the height found so far when it runs out.
int tower_height(const GiNaC::ex& e, long& budget) {
  if (--budget < 0) return 0;
  if (GiNaC::is_a<GiNaC::power>(e)) {
    const int base = tower_height(e.op(0), budget);
    if (GiNaC::is_a<GiNaC::numeric>(e.op(1))) return base;
    return std::max(base, 1 + tower_height(e.op(1), budget));
  }
  int most = 0;
  for (size_t i = 0; i < e.nops(); ++i) most = std::max(most, tower_height(e.op(i), budget));
  return most;
}

[[noreturn]] void too_long(size_t offset, double digits) {
  throw ExprError{offset, fmt::format("expected exact numbers of at most {:g} digits, got an "
                                      "operation that builds one of about {:.3g} digits",
                                      kMaxDigits, digits)};
}

}  // namespace

// Fuzz findings (tests/hardening/data/fuzz/expression/): 0 to a non-positive power makes GiNaC
// throw from inside pow(), leaking the half-built node; a number to a huge power is evaluated
// exactly, which never finishes — also when the exponent is a fraction (x^(999 + 1/2) is
// x^999 √x) or the number sits inside a product or an earlier power.
void check_power(const GiNaC::ex& base, const GiNaC::ex& exponent, size_t offset) {
  // 0 to a symbolic power: its derivative holds log(0), on which GiNaC throws mid-construction
  // and leaks (fuzz finding "der(0^y)").
  if (base.is_zero() && !GiNaC::is_a<GiNaC::numeric>(exponent))
    throw ExprError{offset, "expected a numeric positive exponent of 0, got a symbolic one"};
  if (!GiNaC::is_a<GiNaC::numeric>(exponent)) {
    // Issue 25 item 4: abs(1/9^9^…^9^x) with 22 nines took 77 s and 3 GB in GiNaC's abs().
    long budget = 100000;
    const int height = 1 + std::max(tower_height(base, budget), tower_height(exponent, budget));
    if (height > kMaxPowerTower)
      throw ExprError{offset, fmt::format("expected powers nested at most {} deep in their "
                                          "exponents (a^b^c is 2), got {}",
                                          kMaxPowerTower, height)};
    return;
  }
  const auto& e = GiNaC::ex_to<GiNaC::numeric>(exponent);
  if (base.is_zero() && !(e.is_real() && e.is_positive()))
    throw ExprError{offset,
                    "expected a positive exponent of 0, got 0 ^ (a number <= 0, or complex)"};
  if (GiNaC::abs(e) > kMaxExponent)  // exact comparison: e may be far beyond double's range
    throw ExprError{offset, fmt::format("expected an exponent of magnitude at most {}, got more",
                                        kMaxExponent)};
  if (!e.is_rational()) return;  // a floating-point power is computed in floating point
  // A number to a fraction with a huge denominator: GiNaC may work through floating point and
  // throw an underflow from inside pow(), leaking the half-built node (fuzz finding
  // "fraction-of-negative-power-leak.txt": (-1/3)^(-1/2^150)).
  if (GiNaC::is_a<GiNaC::numeric>(base) && !e.is_integer() && e.denom() > kMaxDenominator)
    throw ExprError{offset,
                    fmt::format("expected a fractional exponent of a number with a "
                                "denominator of at most {:g}, got one of about {:.3g} "
                                "digits",
                                static_cast<double>(kMaxDenominator), digits_of(e.denom()))};
  const double digits = digits_per_unit_power(base) * GiNaC::abs(e).to_double();
  if (!(digits <= kMaxDigits)) too_long(offset, digits);
}

void check_folded(const GiNaC::ex& result, size_t offset) {
  GiNaC::ex coefficient = result;
  if ((GiNaC::is_a<GiNaC::add>(result) || GiNaC::is_a<GiNaC::mul>(result)) && result.nops() > 0)
    coefficient = result.op(result.nops() - 1);  // the overall coefficient comes last
  if (!GiNaC::is_a<GiNaC::numeric>(coefficient)) return;
  const double digits = digits_of(GiNaC::ex_to<GiNaC::numeric>(coefficient));
  if (!(digits <= kMaxDigits)) too_long(offset, digits);
}

namespace {

/// True when `e` is a non-real number, or a power or function of numbers only whose value is not
/// real (sqrt(-2), asin(2), log(-1) stay unevaluated when exact, and the tape would compute NaN).
bool complex_constant(const GiNaC::ex& e) {
  if (GiNaC::is_a<GiNaC::numeric>(e)) return !GiNaC::ex_to<GiNaC::numeric>(e).is_real();
  if (!GiNaC::is_a<GiNaC::power>(e) && !GiNaC::is_a<GiNaC::function>(e)) return false;
  for (size_t i = 0; i < e.nops(); ++i)
    if (!GiNaC::is_a<GiNaC::numeric>(e.op(i))) return false;
  try {
    const GiNaC::ex value = e.evalf();
    return GiNaC::is_a<GiNaC::numeric>(value) && !GiNaC::ex_to<GiNaC::numeric>(value).is_real();
  } catch (const std::exception&) {
    return false;  // not evaluable here; the operation's own checks answer for it
  }
}

/// complex_constant for `e` or, when `e` is a product, for any of its factors.
bool has_complex_factor(const GiNaC::ex& e) {
  if (!GiNaC::is_a<GiNaC::mul>(e)) return complex_constant(e);
  for (size_t i = 0; i < e.nops(); ++i)
    if (complex_constant(e.op(i))) return true;
  return false;
}

}  // namespace

// Fuzz finding (tests/hardening/data/fuzz/metric/complex-sqrt.txt): sqrt(theta^0 + 0e30 - 2)
// folded to the complex float 1.0*I, which reached the tape compiler as an uncaught exception.
void check_real(const GiNaC::ex& result, size_t offset) {
  bool complex = has_complex_factor(result);
  if (GiNaC::is_a<GiNaC::add>(result))
    for (size_t i = 0; i < result.nops() && !complex; ++i)
      complex = has_complex_factor(result.op(i));
  if (!complex) return;
  std::ostringstream text;
  text << result;
  throw ExprError{offset, fmt::format("expected a real value, got {}, which is not real (a root, "
                                      "logarithm, power or inverse function of a number outside "
                                      "its real domain)",
                                      clip(text.str()))};
}

}  // namespace lagrange::model
