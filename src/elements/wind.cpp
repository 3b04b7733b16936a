#include <fmt/format.h>

#include <cmath>

#include "elements/elements.hpp"
#include "model/model_reader.hpp"
#include "model/vec3_algebra.hpp"

namespace lagrange::elements {

namespace {

using model::dot3;
using model::max_of;

// A component of a unit vector as an exact fraction when one with a small denominator matches
// it to rounding (0, ±1, 3/5, …): rounded numbers in a sum would make the tape's order of
// operations, and so its last bits, depend on GiNaC's term order.
GiNaC::ex exact(double x) {
  for (long den = 1; den <= 1000; ++den) {
    const double num = std::round(x * static_cast<double>(den));
    if (std::abs(num / static_cast<double>(den) - x) <= 1e-15)
      return GiNaC::numeric(static_cast<long>(num), den);
  }
  return x;
}

// A direction given by the user, normalised numerically (it must not depend on the state).
Vec3 unit(model::ModelReader& reader, const YAML::Node& node, const Vec3& v,
          const std::string& what) {
  std::array<double, 3> x{};
  for (size_t k = 0; k < 3; ++k) {
    const auto value = reader.evaluate(v[k]);
    if (!value)
      reader.fail(node, fmt::format("expected {} as numbers or expressions of parameters", what));
    x[k] = *value;
  }
  const double n = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  if (!(n > 0) || !std::isfinite(n))
    reader.fail(node, fmt::format("expected a non-zero {}, got [0, 0, 0]", what));
  return {exact(x[0] / n), exact(x[1] / n), exact(x[2] / n)};
}

}  // namespace

// docs/theory.md §4.5: uniform w = U; logarithmic w = U ln(h/z₀)/ln(h_ref/z₀) for h > z₀ and 0
// below the roughness length; power law w = U (h/h_ref)^a for h > 0 and 0 below the ground.
Vec3 Wind::at(const Vec3& position) const {
  const GiNaC::ex h = dot3(position, up);
  GiNaC::ex w = speed * scale;
  switch (profile) {
    case Profile::Uniform:
      break;
    case Profile::Logarithmic:
      w *= GiNaC::log(max_of(h, roughness) / roughness) / GiNaC::log(reference_height / roughness);
      break;
    case Profile::PowerLaw:
      w *= GiNaC::pow(max_of(h, 0) / reference_height, exponent);
      break;
  }
  return {w * direction[0], w * direction[1], w * direction[2]};
}

void read_wind(model::ModelReader& reader, const YAML::Node& node, ElementContext& ctx) {
  using model::kParams;
  using model::kTime;
  reader.expect_map(node, "wind (a map {profile, speed, direction, …})");
  reader.check_keys(
      node, {"profile", "speed", "direction", "reference_height", "roughness", "exponent", "gust"},
      "wind");
  Wind w;
  const std::string profile =
      node["profile"] ? reader.scalar(node["profile"], "wind profile") : "uniform";
  if (profile == "uniform")
    w.profile = Wind::Profile::Uniform;
  else if (profile == "logarithmic")
    w.profile = Wind::Profile::Logarithmic;
  else if (profile == "power_law")
    w.profile = Wind::Profile::PowerLaw;
  else
    reader.fail(node["profile"],
                fmt::format("expected 'uniform', 'logarithmic' or 'power_law' for the wind "
                            "profile, got '{}'",
                            model::clip(profile)));
  if (!node["speed"]) reader.fail(node, "expected 'speed' in wind (m/s at the reference height)");
  w.speed = reader.scalar_expr(node["speed"], kParams, "wind speed");
  reader.check_sign(w.speed, node["speed"], false, "wind speed");
  if (node["direction"])
    w.direction =
        unit(reader, node["direction"],
             reader.vector_expr(node["direction"], kParams, "wind direction"), "wind direction");
  const Model& m = reader.model();
  if (m.gravity) {
    const Vec3& g = *m.gravity;
    bool numeric = true;
    for (const auto& gk : g) numeric = numeric && reader.evaluate(gk).has_value();
    if (numeric) {
      Vec3 minus_g{-g[0], -g[1], -g[2]};
      w.up = unit(reader, node, minus_g, "gravity (it sets which way is up for the wind)");
    }
  }
  if (node["gust"]) w.scale = reader.scalar_expr(node["gust"], kParams | kTime, "wind gust factor");
  if (node["reference_height"]) {
    w.reference_height =
        reader.scalar_expr(node["reference_height"], kParams, "wind reference height");
    reader.check_sign(w.reference_height, node["reference_height"], true, "wind reference height");
  }
  if (node["roughness"]) {
    w.roughness = reader.scalar_expr(node["roughness"], kParams, "wind roughness length z0");
    reader.check_sign(w.roughness, node["roughness"], true, "roughness length z0");
  }
  // ln(h/z0)/ln(h_ref/z0) reverses the wind for h_ref < z0 and divides by 0 at h_ref = z0
  // (issue 25 item 5): checked whichever of the two was given, defaults included.
  if (w.profile == Wind::Profile::Logarithmic) {
    const auto z0 = reader.evaluate(w.roughness), href = reader.evaluate(w.reference_height);
    if (z0 && href && *z0 >= *href)
      reader.fail(node["roughness"] ? node["roughness"] : node["reference_height"],
                  fmt::format("expected a roughness length z0 below the reference height, got "
                              "z0 = {:g} and reference height {:g}",
                              *z0, *href));
  }
  if (node["exponent"]) {
    w.exponent = reader.scalar_expr(node["exponent"], kParams, "wind power-law exponent");
    reader.check_sign(w.exponent, node["exponent"], false, "power-law exponent");
    // (h/h_ref)^a with a ≥ 100 vanishes below h_ref and overflows above it: no wind shear is
    // that steep (open sea ≈ 0.1, cities ≈ 0.4).
    if (const auto a = reader.evaluate_for_test(w.exponent, [](double x) { return x > 1; });
        a && *a > 1)
      reader.fail(node["exponent"],
                  fmt::format("expected a power-law exponent between 0 and 1 (0.1 over open "
                              "water to 0.4 over cities), got {:g}",
                              *a));
  }
  ctx.wind = w;
}

}  // namespace lagrange::elements
