#include <fmt/format.h>

#include <algorithm>

#include "io/equation_text.hpp"
#include "symbolic/expansion_bound.hpp"

namespace lagrange::io {

namespace {

std::string vec_str(const Vec3& v, Style style) {
  const char* sep = style == Style::Latex ? ",\\ " : ", ";
  return fmt::format("[{}{}{}{}{}]", str(v[0], style), sep, str(v[1], style), sep,
                     str(v[2], style));
}

std::string mat_str(const Mat3& m, Style style) {
  const char* sep = style == Style::Latex ? ",\\ " : ", ";
  return fmt::format("[{}{}{}{}{}]", vec_str(m[0], style), sep, vec_str(m[1], style), sep,
                     vec_str(m[2], style));
}

/// `base` with the body's name as subscript: m_brick or m_{\mathrm{brick}}.
std::string named(const std::string& base, const Body& b, Style style) {
  return style == Style::Latex ? base + "_{\\mathrm{" + latex_escape(b.name) + "}}"
                               : base + "_" + b.name;
}

// Mass, inertia about the centre of mass (body axes) and the centre of mass in the body frame.
void print_inertia(const Body& b, Style style, const LineSink& line) {
  line(named("m", b, style), str(b.mass, style));
  line(named("J", b, style), mat_str(b.inertia, style));
  line(named("c", b, style), vec_str(b.com, style));
}

size_t velocity_index(const Equations& eq, const GiNaC::symbol& v) {
  return static_cast<size_t>(std::find(eq.kin.v.begin(), eq.kin.v.end(), v) - eq.kin.v.begin());
}

// Row i of M a − h = Q − Gᵀλ, with the multipliers by name.
void print_row(const Equations& eq, size_t i, Style style, const LineSink& line) {
  std::string rhs = eq.Q[i].is_zero() ? "" : str(eq.Q[i], style);
  for (size_t r = 0; r < eq.m; ++r) {
    const GiNaC::ex g = eq.G(static_cast<unsigned>(r), static_cast<unsigned>(i));
    if (g.is_zero()) continue;
    const std::string lambda = multiplier_str(eq.model->constraints[r].name, style);
    const bool unit = (g - 1).is_zero() || (g + 1).is_zero();
    const bool plus = (g + 1).is_zero();
    std::string term =
        unit ? lambda
             : fmt::format("({}){}{}", str(g, style), style == Style::Latex ? " " : "*", lambda);
    rhs += rhs.empty() ? (plus ? "" : "-") + term : (plus ? " + " : " - ") + term;
  }
  line(str(eq.euler_lagrange_lhs(i), style), rhs.empty() ? "0" : rhs);
}

void print_free_body(const Equations& eq, const Body& b, Style style, const HeadingSink& heading,
                     const LineSink& line) {
  const bool tex = style == Style::Latex;
  heading(fmt::format("Rigid body '{}': free in SO(3) (docs/theory.md §4.4)", b.name));
  print_inertia(b, style, line);
  heading(tex ? "translation: m \\ddot r + \\partial V/\\partial r = F_r - (\\partial C/\\partial "
                "r)^T \\lambda"
              : fmt::format("{}: translation  m r'' + dV/dr = F_r - (dC/dr)^T lambda", b.name));
  for (size_t k = 0; k < 3; ++k) print_row(eq, velocity_index(eq, b.rd[k]), style, line);
  heading(tex ? "rotation: J \\dot\\omega + \\omega \\times J\\omega + 2P(\\partial V/\\partial R) "
                "= F_{rot} - 2P(\\partial C/\\partial R)^T \\lambda"
              : fmt::format("{}: rotation  J w' + w x (J w) + 2P(dV/dR) = F_rot - 2P(dC/dR)^T "
                            "lambda,  P(A) = unskew(R^T A)",
                            b.name));
  for (size_t k = 0; k < 3; ++k) print_row(eq, velocity_index(eq, b.w[k]), style, line);
  heading(tex ? "kinematics: \\dot r = v,\\ \\dot R = R(\\Omega + \\Xi),\\ \\Xi = "
                "\\frac{\\gamma}{2}((R^T R)^{-1} - 1) \\text{ (shown without } \\Xi)"
              : fmt::format("{}: kinematics  r' = v, R' = R (Omega + Xi), Omega = [w]x, "
                            "Xi = gamma/2 ((R^T R)^-1 - 1) (Xi = 0 on SO(3), not shown)",
                            b.name));
  for (size_t j = 0; j < eq.nq; ++j) {
    const GiNaC::symbol& q = eq.kin.q[j];
    const bool mine = std::find(b.r.begin(), b.r.end(), q) != b.r.end() ||
                      std::find(b.R.begin(), b.R.end(), q) != b.R.end();
    if (!mine) continue;
    line(symbol_str(q, style) + (tex ? "'" : "'"), str(eq.qdot[j].subs(eq.kin.gamma == 0), style));
  }
}

// docs/theory.md §4.4: ω = unskew(RᵀṘ), T = ½ m |ẋ_c|² + ½ ωᵀ I ω.
void print_posed_body(const Equations& eq, const Body& b, Style style, const HeadingSink& heading,
                      const LineSink& line) {
  const Model& model = *eq.model;
  heading(fmt::format("Rigid body '{}': posed by coordinates (docs/theory.md §4.4)", b.name));
  print_inertia(b, style, line);
  const Mat3& R = b.rotation;
  Mat3 Rd;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) Rd[i][j] = model.time_derivative(R[i][j]);
  auto Omega = [&](size_t i, size_t j) {
    return R[0][i] * Rd[0][j] + R[1][i] * Rd[1][j] + R[2][i] * Rd[2][j];
  };
  // Printing does bounded algebra only (symbolic::simplify_within): a body posed by a long chain
  // of joints keeps its ω and T as derived.
  constexpr size_t kTerms = 2000;
  const auto tidy = [&](const GiNaC::ex& e) { return symbolic::simplify_within(e, kTerms); };
  const Vec3 w{tidy((Omega(2, 1) - Omega(1, 2)) / 2), tidy((Omega(0, 2) - Omega(2, 0)) / 2),
               tidy((Omega(1, 0) - Omega(0, 1)) / 2)};
  const Vec3 xc = b.world_point(b.com);
  GiNaC::ex T = 0;
  for (size_t k = 0; k < 3; ++k) {
    const GiNaC::ex v = model.time_derivative(xc[k]);
    T += b.mass / 2 * v * v;
    for (size_t l = 0; l < 3; ++l) T += w[k] * b.inertia[k][l] * w[l] / 2;
  }
  const bool tex = style == Style::Latex;
  line(named("r", b, style), vec_str(b.position, style));
  line(named("R", b, style), mat_str(R, style));
  line(named(tex ? "\\omega" : "w", b, style) +
           (tex ? " = \\mathrm{unskew}(R^T \\dot R)" : " = unskew(R^T R')"),
       vec_str(w, style));
  line(named("T", b, style) + (tex ? " = \\tfrac{m}{2} |v_c|^2 + \\tfrac{1}{2} \\omega^T J \\omega"
                                   : " = m/2 |v_c|^2 + w^T J w/2"),
       str(tidy(T), style));
}

}  // namespace

void print_body_equations(const Equations& eq, Style style, const HeadingSink& heading,
                          const LineSink& line) {
  for (const Body& b : eq.model->bodies) {
    if (b.free)
      print_free_body(eq, b, style, heading, line);
    else
      print_posed_body(eq, b, style, heading, line);
  }
}

}  // namespace lagrange::io
