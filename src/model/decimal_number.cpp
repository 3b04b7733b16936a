#include "model/decimal_number.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace lagrange::model {

namespace {

bool digit(char c) {
  return std::isdigit(static_cast<unsigned char>(c)) != 0;
}

}  // namespace

Decimal read_decimal(const std::string& text) {
  constexpr size_t kMaxLength = 1000;
  if (text.size() > kMaxLength)
    return {0, fmt::format("expected a decimal number of at most {} characters, got {}", kMaxLength,
                           text.size())};
  size_t i = 0;
  bool negative = false;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) negative = text[i++] == '-';
  std::string digits;  // significant digits of the mantissa, the point removed
  long exponent = 0;   // value = digits × 10^exponent
  size_t mantissa_digits = 0;
  for (; i < text.size() && digit(text[i]); ++i, ++mantissa_digits) digits += text[i];
  if (i < text.size() && text[i] == '.')
    for (++i; i < text.size() && digit(text[i]); ++i, ++mantissa_digits) {
      digits += text[i];
      --exponent;
    }
  bool ok = mantissa_digits > 0;
  if (ok && i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    bool minus = false;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) minus = text[i++] == '-';
    ok = i < text.size() && digit(text[i]);
    long e = 0;  // saturates: beyond 10^6 every non-zero mantissa is out of range anyway
    for (; i < text.size() && digit(text[i]); ++i) e = std::min(e * 10 + (text[i] - '0'), 1000000L);
    exponent += minus ? -e : e;
  }
  if (!ok || i != text.size()) return {0, "expected a decimal number such as 0.25, -3 or 1.5e-3"};
  const size_t first = digits.find_first_not_of('0');
  if (first == std::string::npos) return {0, ""};  // 0, whatever its exponent
  digits.erase(0, first);
  // Decimal exponent of the leading digit: the magnitude is in [10^lead, 10^(lead+1)).
  const long lead = exponent + static_cast<long>(digits.size()) - 1;
  const double d = lead > 400 ? HUGE_VAL : lead < -400 ? 0.0 : std::strtod(text.c_str(), nullptr);
  if (!std::isfinite(d))
    return {0, fmt::format("expected a number of magnitude at most {:g}",
                           std::numeric_limits<double>::max())};
  if (std::fabs(d) < std::numeric_limits<double>::min())
    return {0, fmt::format("expected 0 or a number of magnitude at least {:g}",
                           std::numeric_limits<double>::min())};
  if (digits.size() > 40 || std::labs(exponent) > 300) return {GiNaC::numeric(d), ""};
  const GiNaC::numeric n =
      GiNaC::numeric(digits.c_str()) * GiNaC::numeric(10).power(GiNaC::numeric(exponent));
  return {negative ? -n : n, ""};
}

}  // namespace lagrange::model
