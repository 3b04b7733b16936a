#include <fmt/format.h>

#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "io/equation_text.hpp"
#include "lagrange/io.hpp"

namespace lagrange {

namespace {

using io::latex_escape;
using io::str;
using io::Style;
using io::symbol_str;

std::string format_text(const Equations& eq, Style style) {
  const Model& model = *eq.model;
  const bool tex = style == Style::Latex;
  io::EquationWriter out(style);
  const io::LineSink line = out.line_sink();
  const io::HeadingSink heading = out.heading_sink();
  auto multiplier = [&](size_t r) { return io::multiplier_str(model.constraints[r].name, style); };
  // Constraint rates are shown on SO(3), where the drift correction Ξ vanishes (γ → 0); the
  // tape keeps the full expressions (docs/theory.md §4.4).
  auto on_manifold = [&](const GiNaC::ex& e) {
    return eq.kin.has_gamma ? e.subs(eq.kin.gamma == 0) : e;
  };
  auto cname = [&](size_t r) {
    return tex ? "\\mathrm{" + latex_escape(model.constraints[r].name) + "}"
               : model.constraints[r].name;
  };
  if (tex)
    out.raw(fmt::format("% {}: {} coordinates, {} constraints\n", model.name, eq.nq, eq.m));
  else
    out.raw(fmt::format("{} — {} coordinates, {} constraints\n", model.name, eq.nq, eq.m));
  // Plain coordinates are named by q, body velocities by their own names (`brick.wx`).
  auto vname = [&](size_t i) {
    return symbol_str(i < eq.kin.plain ? eq.kin.q[i] : eq.kin.v[i], style);
  };
  heading("Energies");
  line("T", str(eq.T, style));
  line("U", str(eq.U, style));
  line(tex ? "L" : "L",
       eq.m ? str(eq.L, style) + (tex ? " - \\lambda^T C" : " - lambda^T C") : str(eq.L, style));
  io::print_element_equations(model, style, out);
  if (eq.kin.plain > 0)
    heading(tex ? "Euler--Lagrange equations"
                : "Euler-Lagrange equations  d/dt(dL/dq_dot) - dL/dq = Q - G^T lambda");
  for (size_t i = 0; i < eq.kin.plain; ++i) {  // body velocities: in their bodies' sections
    GiNaC::ex rhs = eq.Q[i];
    std::string extra;
    for (size_t r = 0; r < eq.m; ++r)
      if (!eq.G(r, i).is_zero())
        extra += fmt::format(" - ({}){}{}", str(eq.G(r, i), style), tex ? " " : "*", multiplier(r));
    std::string right = rhs.is_zero() && !extra.empty() ? extra.substr(1) : str(rhs, style) + extra;
    line(str(eq.euler_lagrange_lhs(i), style), right);
  }
  if (!model.bodies.empty()) io::print_body_equations(eq, style, heading, line);
  heading("Mass matrix M(q)");
  for (size_t i = 0; i < eq.nv; ++i)
    for (size_t j = 0; j <= i; ++j)
      if (!eq.M(i, j).is_zero())
        line(fmt::format("M_{{{}{}}}", i + 1, j + 1), str(eq.M(i, j), style));
  heading("Forcing h(q, v) + Q");
  for (size_t i = 0; i < eq.nv; ++i)
    line(fmt::format("(h+Q)_{{{}}}", vname(i)), str(eq.h[i] + eq.Q[i], style));
  if (eq.m > 0) {
    heading(tex ? "Constraints, index-3: C = 0" : "Constraints (index-3 DAE: C = 0)");
    for (size_t r = 0; r < eq.m; ++r) line("C_{" + cname(r) + "}", str(eq.C[r], style));
    heading("Constraint Jacobian G = dC/dq");
    for (size_t r = 0; r < eq.m; ++r)
      for (size_t j = 0; j < eq.nv; ++j)
        if (!eq.G(r, j).is_zero())
          line(fmt::format("G_{{{},{}}}", cname(r), vname(j)), str(eq.G(r, j), style));
    heading(tex ? "Index-1 form: G a + c = 0" : "Index-1 form (C'' = G a + c = 0)");
    for (size_t r = 0; r < eq.m; ++r) {
      std::string lhs;
      for (size_t j = 0; j < eq.nv; ++j)
        if (!eq.G(r, j).is_zero())
          lhs += fmt::format("{}({})*{}", lhs.empty() ? "" : " + ", str(eq.G(r, j), style),
                             symbol_str(eq.kin.a[j], style));
      line(lhs + " + " + str(on_manifold(eq.c[r]), style), "0");
    }
    heading(tex ? "Baumgarte: G a + c + 2 alpha Cdot + alpha^2 C = 0"
                : "Baumgarte-stabilised (C'' + 2 alpha C' + alpha^2 C = 0), with");
    for (size_t r = 0; r < eq.m; ++r)
      line((tex ? "\\dot{C}_{" : "Cdot_{") + cname(r) + "}", str(on_manifold(eq.Cdot[r]), style));
  }
  if (eq.m == 0 && eq.nv <= 3 && eq.nq == eq.nv) {
    heading(tex ? "Accelerations a = M^{-1} (h + Q)" : "Accelerations a = M^-1 (h + Q)");
    if (const auto acc = solve_accelerations(eq, kSolvedAccelerationTerms)) {
      for (size_t i = 0; i < eq.nv; ++i)
        line(symbol_str(eq.kin.a[i], style), str((*acc)[i], style));
    } else {
      const std::string why = fmt::format(
          "not solved symbolically: Cramer's rule would expand to more than {} terms; M and "
          "h + Q above define them (lagrange simulate and eval evaluate them numerically)",
          kSolvedAccelerationTerms);
      out.raw(tex ? "% " + why + "\n" : "  " + why + "\n");
    }
  }
  return out.finish();
}

// The recursive formulation has no M or h worth printing: its accelerations are a chain of named
// intermediates (docs/theory.md §4.9). Say so, with what the elements lowered, and with
// `definitions` the chain itself.
std::string recursive_text(const Equations& eq, const std::string& format, bool definitions) {
  const Model& model = *eq.model;
  const std::string what = fmt::format(
      "accelerations from the articulated-body algorithm over {} joints ({} named "
      "intermediates){}",
      model.tree.size(), eq.definitions.size(),
      definitions ? "" : "; lagrange derive --form recursive prints them");
  const bool tex = format == "latex";
  const Style style = tex ? Style::Latex : Style::Text;
  if (format == "json") {
    nlohmann::json j;
    j["name"] = model.name;
    j["coordinates"] = eq.kin.q_names;
    j["recursive"] = what;
    if (definitions) {
      for (const auto& [name, value] : eq.definitions)
        j["definitions"].push_back({name.get_name(), str(value, Style::Text)});
      for (size_t i = 0; i < eq.nv; ++i) j["accelerations"].push_back(str(eq.h[i], Style::Text));
    }
    return j.dump(2) + "\n";
  }
  io::EquationWriter out(style);
  const io::HeadingSink heading = out.heading_sink();
  const io::LineSink line = out.line_sink();
  out.raw(fmt::format(tex ? "% {}: {} coordinates\n" : "{} — {} coordinates\n", model.name, eq.nq));
  io::print_element_equations(model, style, out);
  heading("Equations of motion");
  out.raw(tex ? "% " + what + "\n" : "  " + what + "\n");
  if (definitions) {
    heading(tex ? "Articulated-body algorithm"
                : "Articulated-body algorithm (in evaluation order)");
    for (const auto& [name, value] : eq.definitions)
      line(symbol_str(name, style), str(value, style));
    heading("Accelerations");
    for (size_t i = 0; i < eq.nv; ++i) line(symbol_str(eq.kin.a[i], style), str(eq.h[i], style));
  }
  return out.finish();
}

std::string format_json(const Equations& eq) {
  const Model& model = *eq.model;
  auto s = [](const GiNaC::ex& e) { return str(e, Style::Text); };
  auto l = [](const GiNaC::ex& e) { return str(e, Style::Latex); };
  nlohmann::json j;
  j["name"] = model.name;
  for (const auto& c : eq.kin.q_names) j["coordinates"].push_back(c);
  for (const auto& c : eq.kin.v_names) j["velocities"].push_back(c);
  for (size_t i = 0; i < eq.nq; ++i) j["qdot"].push_back(s(eq.qdot[i]));
  j["T"] = s(eq.T);
  j["U"] = s(eq.U);
  j["L"] = s(eq.L);
  j["latex"]["T"] = l(eq.T);
  j["latex"]["U"] = l(eq.U);
  for (size_t i = 0; i < eq.nv; ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (size_t k = 0; k < eq.nv; ++k) row.push_back(s(eq.M(i, k)));
    j["M"].push_back(row);
    j["h"].push_back(s(eq.h[i]));
    j["Q"].push_back(s(eq.Q[i]));
    j["euler_lagrange"].push_back(s(eq.euler_lagrange_lhs(i)));
  }
  for (size_t r = 0; r < eq.m; ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (size_t k = 0; k < eq.nv; ++k) row.push_back(s(eq.G(r, k)));
    j["constraints"].push_back({{"name", model.constraints[r].name},
                                {"C", s(eq.C[r])},
                                {"Cdot", s(eq.Cdot[r])},
                                {"c", s(eq.c[r])},
                                {"G", row}});
  }
  return j.dump(2) + "\n";
}

}  // namespace

std::string format_recursive(const Equations& eq, const std::string& format) {
  if (format != "text" && format != "latex" && format != "json")
    throw std::invalid_argument("unknown format '" + format + "'; expected text, latex or json");
  if (!eq.recursive) throw std::invalid_argument("format_recursive: the equations are Lagrangian");
  return recursive_text(eq, format, true);
}

std::string format_equations(const Equations& eq, const std::string& format, bool expand) {
  if (format != "text" && format != "latex" && format != "json")
    throw std::invalid_argument("unknown format '" + format + "'; expected text, latex or json");
  if (eq.recursive) return recursive_text(eq, format, false);
  if (!expand) {
    if (io::expanded_size(eq, kFullExpansionLimit + 1) > kFullExpansionLimit)
      return io::format_equations_cse(eq, format);
  }
  if (format == "text") return format_text(eq, Style::Text);
  if (format == "latex") return format_text(eq, Style::Latex);
  if (format == "json") return format_json(eq);
  throw std::invalid_argument("unknown format '" + format + "'; expected text, latex or json");
}

}  // namespace lagrange
