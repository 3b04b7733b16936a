// The cases of a study: a grid of --vary axes, each point combined with seeded random draws.

#include <fmt/format.h>

#include <cmath>
#include <set>

#include "lagrange/sweep.hpp"
#include "sweep/spec_text.hpp"

namespace lagrange::sweep {

namespace {

/// "3 m × 4 l × 10 draws": how the number of cases comes about, for a message.
std::string study_shape(const std::vector<Axis>& axes, const std::vector<RandomParameter>& random,
                        size_t draws) {
  std::string text;
  for (const auto& a : axes)
    text += fmt::format("{}{} {}", text.empty() ? "" : " × ", a.values.size(), a.name);
  if (!random.empty()) text += fmt::format("{}{} draws", text.empty() ? "" : " × ", draws);
  return text;
}

}  // namespace

Axis parse_axis(const std::string& spec) {
  const auto [name, rest] =
      name_and_value(spec, "--vary", "NAME=START:STOP:COUNT or NAME=V1,V2,...");
  Axis axis{name, {}};
  const std::string context = fmt::format("--vary {}", spec);
  if (rest.find(':') != std::string::npos) {
    const std::vector<std::string> parts = split(rest, ':');
    if (parts.size() != 3)
      throw StudyError(fmt::format("{}: expected START:STOP:COUNT, got '{}'", context, rest));
    const double start = finite_number(parts[0], context + " (START)");
    const double stop = finite_number(parts[1], context + " (STOP)");
    const double count = finite_number(parts[2], context + " (COUNT)");
    if (!(count >= 1 && count <= static_cast<double>(kMaxStudyCases)) || count != std::floor(count))
      throw StudyError(
          fmt::format("{}: COUNT must be a whole number of values from 1 to {}, got "
                      "'{}'",
                      context, kMaxStudyCases, parts[2]));
    if (count == 1 && start != stop)
      throw StudyError(fmt::format("{}: one value cannot span {} to {}; give COUNT 2 or more",
                                   context, parts[0], parts[1]));
    const auto n = static_cast<size_t>(count);
    // Evenly spaced, both ends exact: start + (stop - start) i / (n - 1).
    if (!std::isfinite(stop - start))
      throw StudyError(
          fmt::format("{}: STOP - START overflows a double; the values between them "
                      "would not be finite numbers",
                      context));
    for (size_t i = 0; i < n; ++i)
      axis.values.push_back(i + 1 == n ? stop
                                       : start + (stop - start) * static_cast<double>(i) /
                                                     static_cast<double>(n - 1));
  } else {
    if (rest.empty()) throw StudyError(fmt::format("{}: no values after '='", context));
    for (const auto& v : split(rest, ',')) axis.values.push_back(finite_number(v, context));
  }
  return axis;
}

std::vector<Case> make_cases(const std::vector<Axis>& axes,
                             const std::vector<RandomParameter>& random, size_t samples,
                             std::uint64_t seed) {
  std::set<std::string> names;
  for (const auto& a : axes)
    if (!names.insert(a.name).second)
      throw StudyError(fmt::format("parameter '{}' is varied twice", a.name));
  for (const auto& r : random)
    if (!names.insert(r.name).second)
      throw StudyError(fmt::format("parameter '{}' is varied twice", r.name));
  if (names.empty()) throw StudyError("nothing varies: give --vary or --random");
  if (!random.empty() && samples == 0)
    throw StudyError("--random needs --samples N with N at least 1");
  // The size is checked before it is used: a product of sizes can wrap (issue 37 item 3).
  const size_t draws = random.empty() ? 1 : samples;
  double figure = static_cast<double>(draws);
  for (const auto& a : axes) figure *= static_cast<double>(a.values.size());
  if (figure > static_cast<double>(kMaxStudyCases))
    throw StudyError(
        fmt::format("the study has {:.4g} cases ({}), more than the {} a study may "
                    "have (docs/sweeps.md)",
                    figure, study_shape(axes, random, draws), kMaxStudyCases));
  size_t grid = 1;
  for (const auto& a : axes) grid *= a.values.size();
  std::mt19937_64 rng(seed);
  std::vector<Case> cases;
  cases.reserve(grid * draws);
  for (size_t g = 0; g < grid; ++g) {
    std::vector<std::pair<std::string, double>> point;
    size_t rest = g;
    for (size_t i = axes.size(); i-- > 0;) {  // the last axis varies fastest
      point.emplace_back(axes[i].name, axes[i].values[rest % axes[i].values.size()]);
      rest /= axes[i].values.size();
    }
    std::reverse(point.begin(), point.end());
    for (size_t s = 0; s < draws; ++s) {
      Case c{cases.size(), point};
      for (const auto& r : random) {
        const double x = sample(r.distribution, rng);
        if (!std::isfinite(x))
          throw StudyError(
              fmt::format("--random {}={}: draw {} of case {} is {}, not a finite "
                          "number",
                          r.name, r.distribution.text, s + 1, cases.size(), x));
        c.values.emplace_back(r.name, x);
      }
      cases.push_back(std::move(c));
    }
  }
  return cases;
}

}  // namespace lagrange::sweep
