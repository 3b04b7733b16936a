#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "lagrange/rigid_body.hpp"
#include "model/model_reader.hpp"

namespace lagrange::model {

namespace {

/// ‖RᵀR − 1‖_F and det R must be within this of 0 and +1 (as for a free body's orientation).
constexpr double kRotationTolerance = 1e-9;
/// States tried besides the initial one, and how far from it the coordinates move.
constexpr int kRandomStates = 4;
constexpr double kSpread = 2.0;

/// The nine entries of `R` at `values`, or nothing where one is not a finite real number.
std::optional<Rotation> evaluate_matrix(const Mat3& R, const GiNaC::exmap& values) {
  Rotation out{};
  try {
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) {
        const GiNaC::ex x = GiNaC::evalf(R[i][j].subs(values));
        if (!GiNaC::is_a<GiNaC::numeric>(x) || !GiNaC::ex_to<GiNaC::numeric>(x).is_real())
          return std::nullopt;
        out[3 * i + j] = GiNaC::ex_to<GiNaC::numeric>(x).to_double();
        if (!std::isfinite(out[3 * i + j])) return std::nullopt;
      }
  } catch (const std::exception&) {
    return std::nullopt;  // a pole at this state (division by zero): not a state to judge by
  }
  return out;
}

}  // namespace

// The initial state (t = 0, the coordinates' initial values and rates) and kRandomStates states
// drawn around it with a fixed seed: coordinates moved by up to ±kSpread, random rates, t in
// [0, 10], inputs and their derivatives following t, free bodies at their initial orientation
// with random ω.
std::vector<ModelReader::SampledState> ModelReader::sample_states() const {
  std::mt19937 random(20261122);
  std::uniform_real_distribution<double> offset(-kSpread, kSpread), time(0.0, 10.0);
  std::vector<SampledState> states;
  for (int k = 0; k <= kRandomStates; ++k) {
    SampledState s;
    for (const Parameter& p : m_.parameters) s.values[p.sym] = GiNaC::numeric(p.value);
    const double t = k == 0 ? 0.0 : time(random);
    s.values[m_.t] = GiNaC::numeric(t);
    s.shown["t"] = t;
    for (const Coordinate& c : m_.coordinates) {
      const double q = k == 0 ? c.initial : c.initial + offset(random);
      s.values[c.q] = GiNaC::numeric(q);
      s.values[c.v] = GiNaC::numeric(k == 0 ? c.rate : offset(random));
      s.shown[c.name] = q;
    }
    try {
      for (const Input& u : m_.inputs) {
        s.values[u.u] = GiNaC::evalf(u.expr.subs(s.values));
        s.values[u.ud] = GiNaC::evalf(u.expr.diff(m_.t).subs(s.values));
        s.values[u.udd] = GiNaC::evalf(u.expr.diff(m_.t, 2).subs(s.values));
      }
    } catch (const std::exception&) {
      continue;  // an input with a pole at this t
    }
    for (const Body& b : m_.bodies)
      if (b.free)
        for (size_t i = 0; i < 9; ++i) s.values[b.R[i]] = GiNaC::numeric(b.R0[i]);
    for (const Body& b : m_.bodies)
      if (b.free)
        for (size_t i = 0; i < 3; ++i) s.values[b.w[i]] = GiNaC::numeric(offset(random));
    s.initial = k == 0;
    states.push_back(std::move(s));
  }
  return states;
}

// The checks below evaluate a rotation at states drawn around the initial one: a trace cannot
// follow what they find.
void ModelReader::untraced_rotation(const Body& body) const {
  for (const Vec3& row : body.rotation)
    for (const GiNaC::ex& e : row)
      untraceable(e, "the rotation of body '" + body.name + "', checked at sampled states");
}

// A posed body's `rotation:` must be a rotation wherever the coordinates go (docs/theory.md §4.4:
// ω = unskew(RᵀṘ) assumes RᵀR = 1). Checked numerically at the sampled states.
void ModelReader::check_posed_rotation(const Body& body, const YAML::Node& node) const {
  untraced_rotation(body);
  std::vector<std::string> used;  // the names R depends on, for the message
  auto depends = [&](const GiNaC::ex& s) {
    for (const Vec3& row : body.rotation)
      for (const GiNaC::ex& e : row)
        if (e.has(s)) return true;
    return false;
  };
  for (const Coordinate& c : m_.coordinates)
    if (depends(c.q)) used.push_back(c.name);
  if (depends(m_.t)) used.push_back("t");
  for (const SampledState& s : sample_states()) {
    const std::optional<Rotation> R = evaluate_matrix(body.rotation, s.values);
    if (!R) continue;
    const double err = orthonormality_error(R->data()), det = determinant(R->data());
    if (err < kRotationTolerance && std::abs(det - 1) < kRotationTolerance) continue;
    std::string at;
    for (const std::string& name : used)
      at += fmt::format("{}{} = {:.6g}", at.empty() ? "" : ", ", name, s.shown.at(name));
    const std::string where = s.initial ? "at the initial state" : "at a state drawn by the check";
    fail(node, fmt::format("expected a rotation matrix (RᵀR = 1 and det R = +1, to {:g}) for the "
                           "rotation of body '{}', got {} {}{}",
                           kRotationTolerance, body.name,
                           err < kRotationTolerance ? fmt::format("det R = {:.6g}", det)
                                                    : fmt::format("‖RᵀR − 1‖ = {:.3g}", err),
                           where, at.empty() ? "" : " (" + at + ")"));
  }
}

// ω = unskew(RᵀṘ) (docs/theory.md §4.4) at the sampled states: the body axis it always lies
// along, if there is one (a planar link posed by rot_z(q) turns about z only).
std::optional<size_t> ModelReader::single_spin_axis(const Body& body) const {
  untraced_rotation(body);
  Mat3 Rdot;
  try {
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) Rdot[i][j] = m_.time_derivative(body.rotation[i][j]);
  } catch (const std::logic_error&) {
    return std::nullopt;  // a rotation through accelerations: no claim
  }
  std::array<double, 3> largest{};
  for (const SampledState& s : sample_states()) {
    const std::optional<Rotation> R = evaluate_matrix(body.rotation, s.values);
    const std::optional<Rotation> Rd = evaluate_matrix(Rdot, s.values);
    if (!R || !Rd) continue;
    auto omega = [&](size_t a, size_t b) {  // (RᵀṘ)_ab
      double x = 0;
      for (size_t k = 0; k < 3; ++k) x += (*R)[3 * k + a] * (*Rd)[3 * k + b];
      return std::abs(x);
    };
    const std::array<double, 3> w{omega(2, 1), omega(0, 2), omega(1, 0)};
    for (size_t a = 0; a < 3; ++a) largest[a] = std::max(largest[a], w[a]);
  }
  const double top = std::max({largest[0], largest[1], largest[2]});
  if (!(top > 0)) return std::nullopt;
  size_t axis = 3;
  for (size_t a = 0; a < 3; ++a)
    if (largest[a] > kRotationTolerance * top) {
      if (axis != 3) return std::nullopt;
      axis = a;
    }
  return axis;
}

}  // namespace lagrange::model
