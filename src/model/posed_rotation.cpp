#include <fmt/format.h>

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

// A posed body's `rotation:` must be a rotation wherever the coordinates go (docs/theory.md §4.4:
// ω = unskew(RᵀṘ) assumes RᵀR = 1). Checked numerically at the initial state and at a few
// states drawn around it (fixed seed), with t and the inputs moving too.
void ModelReader::check_posed_rotation(const Body& body, const YAML::Node& node) const {
  std::mt19937 random(20261122);
  std::uniform_real_distribution<double> offset(-kSpread, kSpread), time(0.0, 10.0);
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
  for (int k = 0; k <= kRandomStates; ++k) {
    GiNaC::exmap values;
    std::map<std::string, double> shown;
    for (const Parameter& p : m_.parameters) values[p.sym] = GiNaC::numeric(p.value);
    const double t = k == 0 ? 0.0 : time(random);
    values[m_.t] = GiNaC::numeric(t);
    shown["t"] = t;
    for (const Coordinate& c : m_.coordinates) {
      const double q = k == 0 ? c.initial : c.initial + offset(random);
      values[c.q] = GiNaC::numeric(q);
      values[c.v] = GiNaC::numeric(k == 0 ? c.rate : offset(random));
      shown[c.name] = q;
    }
    for (const Input& u : m_.inputs) values[u.u] = GiNaC::evalf(u.expr.subs(values));
    for (const Body& b : m_.bodies)
      if (b.free)
        for (size_t i = 0; i < 9; ++i) values[b.R[i]] = GiNaC::numeric(b.R0[i]);
    const std::optional<Rotation> R = evaluate_matrix(body.rotation, values);
    if (!R) continue;
    const double err = orthonormality_error(R->data()), det = determinant(R->data());
    if (err < kRotationTolerance && std::abs(det - 1) < kRotationTolerance) continue;
    std::string at;
    for (const std::string& name : used)
      at += fmt::format("{}{} = {:.6g}", at.empty() ? "" : ", ", name, shown[name]);
    const std::string where = k == 0 ? "at the initial state" : "at a state drawn by the check";
    fail(node, fmt::format("expected a rotation matrix (RᵀR = 1 and det R = +1, to {:g}) for the "
                           "rotation of body '{}', got {} {}{}",
                           kRotationTolerance, body.name,
                           err < kRotationTolerance ? fmt::format("det R = {:.6g}", det)
                                                    : fmt::format("‖RᵀR − 1‖ = {:.3g}", err),
                           where, at.empty() ? "" : " (" + at + ")"));
  }
}

}  // namespace lagrange::model
