#pragma once
// Bounds on the exact numbers the expression reader folds (issue 8, item 12). GiNaC evaluates
// powers of numbers exactly, so a short text such as (((2*x)^999)^999)^999 asks for a number of
// hundreds of millions of digits; each check here refuses such a fold before GiNaC starts it.

#include <ginac/ginac.h>

#include <cstddef>

namespace lagrange::model {

/// Largest |exponent| of a power with a numeric exponent.
constexpr int kMaxExponent = 1000;
/// Largest exact number (numerator or denominator, in decimal digits) a fold may build.
constexpr double kMaxDigits = 10000;
/// Largest denominator of a fractional exponent of a number (2^(1/10^12) is fine).
constexpr long long kMaxDenominator = 1000000000000LL;
/// Deepest tower of powers with non-numeric exponents (a^b^c is 2): GiNaC's sign and
/// realness queries (abs, 1/P, derivatives) visit a tower's levels twice each, 2^height work.
constexpr int kMaxPowerTower = 8;

/// Throws ExprError at `offset` for powers GiNaC must not be asked for: 0 to a symbolic or
/// non-positive power, an exponent beyond kMaxExponent, a tower of symbolic powers higher
/// than kMaxPowerTower, a number to a fraction whose
/// denominator exceeds kMaxDenominator, and a power whose exact numbers — the
/// base's numeric factors raised to the exponent — would exceed kMaxDigits.
void check_power(const GiNaC::ex& base, const GiNaC::ex& exponent, size_t offset);

/// Throws ExprError at `offset` when the number an operation folded (the result itself, or the
/// numeric coefficient of a sum or product) has more than kMaxDigits digits.
void check_folded(const GiNaC::ex& result, size_t offset);

/// Throws ExprError at `offset` when a function or power of real operands came out complex
/// (sqrt(-1) = I, sqrt(-2), log(-1), asin(2)): a non-real number, or a power or function of
/// numbers whose value is not real, as the result, a factor or a term. Model expressions are
/// real; the tape has no complex type and would compute NaN.
void check_real(const GiNaC::ex& result, size_t offset);

}  // namespace lagrange::model
