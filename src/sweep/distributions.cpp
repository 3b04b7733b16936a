// Random parameters: `normal(μ,σ)`, `uniform(a,b)`, `lognormal(μ,σ)` drawn from a seeded
// mt19937_64 (docs/theory.md §9.1).

#include <fmt/format.h>

#include <cmath>

#include "lagrange/sweep.hpp"
#include "sweep/spec_text.hpp"

namespace lagrange::sweep {

namespace {

// docs/theory.md §9.1: a uniform double in (0, 1) from the top 53 bits of one 64-bit draw.
double open_unit(std::mt19937_64& rng) {
  return (static_cast<double>(rng() >> 11) + 0.5) * 0x1.0p-53;
}

// docs/theory.md §9.1, Box–Muller: one standard normal from two uniforms.
double standard_normal(std::mt19937_64& rng) {
  const double u1 = open_unit(rng), u2 = open_unit(rng);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

}  // namespace

RandomParameter parse_random(const std::string& spec) {
  const auto [name, rest] =
      name_and_value(spec, "--random",
                     "NAME=normal(MU,SIGMA), NAME=uniform(LOW,HIGH) or NAME=lognormal(MU,SIGMA)");
  const std::string context = fmt::format("--random {}", spec);
  const auto open = rest.find('(');
  if (open == std::string::npos || rest.back() != ')')
    throw StudyError(fmt::format(
        "{}: expected normal(MU,SIGMA), uniform(LOW,HIGH) or lognormal(MU,SIGMA)", context));
  const std::string kind = trim(rest.substr(0, open));
  const std::vector<std::string> args = split(rest.substr(open + 1, rest.size() - open - 2), ',');
  Distribution d;
  d.text = rest;
  if (kind == "normal") {
    d.kind = Distribution::Kind::Normal;
  } else if (kind == "uniform") {
    d.kind = Distribution::Kind::Uniform;
  } else if (kind == "lognormal") {
    d.kind = Distribution::Kind::LogNormal;
  } else {
    throw StudyError(fmt::format(
        "{}: unknown distribution '{}' (expected normal, uniform or lognormal)", context, kind));
  }
  if (args.size() != 2)
    throw StudyError(fmt::format("{}: {} takes two numbers, got {}", context, kind, args.size()));
  d.a = finite_number(args[0], context);
  d.b = finite_number(args[1], context);
  if (d.kind == Distribution::Kind::Uniform && !(d.a < d.b))
    throw StudyError(fmt::format("{}: uniform(LOW,HIGH) needs LOW < HIGH", context));
  if (d.kind != Distribution::Kind::Uniform && !(d.b >= 0))
    throw StudyError(fmt::format("{}: SIGMA must not be negative", context));
  return {name, d};
}

double sample(const Distribution& d, std::mt19937_64& rng) {
  switch (d.kind) {
    case Distribution::Kind::Uniform:
      return d.a + (d.b - d.a) * open_unit(rng);
    case Distribution::Kind::Normal:
      return d.a + d.b * standard_normal(rng);
    case Distribution::Kind::LogNormal:
      return std::exp(d.a + d.b * standard_normal(rng));
  }
  return 0.0;
}

}  // namespace lagrange::sweep
