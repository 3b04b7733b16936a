// `lagrange derive --form manipulator`: D(q), the Christoffel symbols, C(q, q̇), g(q) and τ
// (docs/theory.md §4.8) as text, LaTeX or JSON.

#include <fmt/format.h>

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "io/equation_text.hpp"
#include "lagrange/io.hpp"

namespace lagrange {

namespace {

using io::str;
using io::Style;

/// "121" for up to nine coordinates, "1,2,1" beyond.
std::string indices(size_t n, std::initializer_list<size_t> ix) {
  std::string s;
  for (size_t i : ix) s += (s.empty() || n <= 9 ? "" : ",") + std::to_string(i + 1);
  return s;
}

/// A 3 × n matrix on one line: [[a, b], …] or a LaTeX pmatrix.
std::string matrix_str(const GiNaC::matrix& J, Style style) {
  const bool tex = style == Style::Latex;
  std::string out = tex ? "\\begin{pmatrix} " : "[";
  for (unsigned r = 0; r < J.rows(); ++r) {
    out += r ? (tex ? " \\\\ " : ", [") : (tex ? "" : "[");
    for (unsigned c = 0; c < J.cols(); ++c)
      out += (c ? (tex ? " & " : ", ") : "") + str(J(r, c), style);
    out += tex ? "" : "]";
  }
  return out + (tex ? " \\end{pmatrix}" : "]");
}

std::string format_text(const ManipulatorForm& f, Style style) {
  const Equations& eq = *f.eq;
  const size_t n = eq.nv;
  const bool tex = style == Style::Latex;
  io::EquationWriter out(style);
  const io::LineSink line = out.line_sink();
  const io::HeadingSink heading = out.heading_sink();
  std::string coords;
  for (size_t i = 0; i < n; ++i) coords += (i ? ", " : "") + eq.kin.q_names[i];
  out.raw(
      fmt::format("{}{} — manipulator form D(q) q_ddot + C(q, q_dot) q_dot + g(q) = tau, q = "
                  "({})\n",
                  tex ? "% " : "", eq.model->name, coords));
  heading("Inertia matrix D(q)");
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i; j < n; ++j)
      line(fmt::format("d_{{{}}}", indices(n, {i, j})), str(f.D(i, j), style));
  heading(tex ? "Christoffel symbols (non-zero)"
              : "Christoffel symbols c_ijk = 1/2 (d d_kj/d q_i + d d_ki/d q_j - d d_ij/d q_k), "
                "non-zero");
  if (f.christoffel.empty()) out.raw(tex ? "  % none\n" : "  (none)\n");
  for (const Christoffel& c : f.christoffel)
    line(fmt::format("c_{{{}}}", indices(n, {c.i, c.j, c.k})), str(c.value, style));
  heading(tex ? "C(q, \\dot q)" : "C(q, q_dot), C_kj = sum_i c_ijk q_dot_i");
  for (size_t k = 0; k < n; ++k)
    for (size_t j = 0; j < n; ++j)
      if (!f.C(k, j).is_zero())
        line(fmt::format("C_{{{}}}", indices(n, {k, j})), str(f.C(k, j), style));
  heading(tex ? "g(q)" : "Gravity g(q) = dP/dq");
  for (size_t k = 0; k < n; ++k) line(fmt::format("g_{{{}}}", k + 1), str(f.g[k], style));
  if (!f.jacobians.empty())
    heading(tex ? "Link Jacobians: v_c = J_v \\dot q, \\omega = J_\\omega \\dot q (world axes)"
                : "Link Jacobians: centre-of-mass velocity v_c = J_v q_dot, angular velocity "
                  "omega = J_w q_dot (world axes)");
  for (const LinkJacobian& J : f.jacobians) {
    const std::string link = tex ? "\\mathrm{" + io::latex_escape(J.link) + "}" : J.link;
    line(tex ? "J_{v," + link + "}" : "J_v(" + link + ")", matrix_str(J.Jv, style));
    line(tex ? "J_{\\omega," + link + "}" : "J_w(" + link + ")", matrix_str(J.Jw, style));
  }
  heading(tex ? "\\tau" : "Joint forces tau (generalised forces)");
  for (size_t k = 0; k < n; ++k) line(fmt::format("tau_{{{}}}", k + 1), str(f.tau[k], style));
  return out.finish();
}

std::string format_json(const ManipulatorForm& f) {
  const Equations& eq = *f.eq;
  const size_t n = eq.nv;
  auto s = [](const GiNaC::ex& e) { return str(e, Style::Text); };
  nlohmann::json j;
  j["name"] = eq.model->name;
  j["form"] = "manipulator";
  for (const auto& c : eq.kin.q_names) j["coordinates"].push_back(c);
  for (size_t i = 0; i < n; ++i) {
    nlohmann::json d = nlohmann::json::array(), c = nlohmann::json::array();
    for (size_t k = 0; k < n; ++k) {
      d.push_back(s(f.D(i, k)));
      c.push_back(s(f.C(i, k)));
    }
    j["D"].push_back(d);
    j["C"].push_back(c);
    j["g"].push_back(s(f.g[i]));
    j["tau"].push_back(s(f.tau[i]));
    j["latex"]["g"].push_back(str(f.g[i], Style::Latex));
  }
  j["christoffel"] = nlohmann::json::array();
  for (const Christoffel& c : f.christoffel)
    j["christoffel"].push_back({{"i", c.i + 1},
                                {"j", c.j + 1},
                                {"k", c.k + 1},
                                {"value", s(c.value)},
                                {"latex", str(c.value, Style::Latex)}});
  j["jacobians"] = nlohmann::json::array();
  for (const LinkJacobian& J : f.jacobians) {
    nlohmann::json jv, jw;
    for (unsigned r = 0; r < 3; ++r) {
      nlohmann::json rv = nlohmann::json::array(), rw = nlohmann::json::array();
      for (unsigned c = 0; c < J.Jv.cols(); ++c) {
        rv.push_back(s(J.Jv(r, c)));
        rw.push_back(s(J.Jw(r, c)));
      }
      jv.push_back(rv);
      jw.push_back(rw);
    }
    j["jacobians"].push_back({{"link", J.link}, {"Jv", jv}, {"Jw", jw}});
  }
  return j.dump(2) + "\n";
}

}  // namespace

std::string format_manipulator(const ManipulatorForm& form, const std::string& format) {
  if (format == "text") return format_text(form, Style::Text);
  if (format == "latex") return format_text(form, Style::Latex);
  if (format == "json") return format_json(form);
  throw std::invalid_argument("unknown format '" + format + "'; expected text, latex or json");
}

}  // namespace lagrange
