#pragma once
// Decimal floating-point text read into an exact number with bounded work (issue 25 item 3):
// URDF attributes such as xyz="0e999999999999 0 0" must neither hang in an exact power of ten
// nor pass hexadecimal or other strtod extensions through to CLN.

#include <ginac/ginac.h>

#include <string>

namespace lagrange::model {

/// A decimal number read from text, or why the text is not one.
struct Decimal {
  GiNaC::ex value;      ///< the number (meaningful when `problem` is empty)
  std::string problem;  ///< what was expected and not found, "" on success
};

/// Reads `text` as [+-]digits[.digits][(e|E)[+-]digits] (or .digits): exact when it has at
/// most 40 significant digits and a decimal exponent within ±300, the nearest double otherwise;
/// refuses other syntax (hex, inf, nan, spaces), |x| beyond double's range, non-zero |x| below
/// 2.2e-308, and text longer than 1000 characters. Linear in the text's length.
Decimal read_decimal(const std::string& text);

}  // namespace lagrange::model
