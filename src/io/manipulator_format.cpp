// `lagrange derive --form manipulator`: D(q), the Christoffel symbols, C(q, q̇), g(q) and τ
// (docs/theory.md §4.8) as text, LaTeX or JSON; a large arm's through named common
// subexpressions, as `derive` prints large models (src/io/equations_cse.cpp).

#include <fmt/format.h>

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "compile/ginac_util.hpp"
#include "io/equation_text.hpp"
#include "lagrange/io.hpp"
#include "lagrange/tape.hpp"

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

/// The text of an expression in the output: written out in full, or through named common
/// subexpressions.
using Render = std::function<std::string(const GiNaC::ex&)>;

/// A 3 × n matrix on one line: [[a, b], …] or a LaTeX pmatrix.
std::string matrix_str(const GiNaC::matrix& J, Style style, const Render& render) {
  const bool tex = style == Style::Latex;
  std::string out = tex ? "\\begin{pmatrix} " : "[";
  for (unsigned r = 0; r < J.rows(); ++r) {
    out += r ? (tex ? " \\\\ " : ", [") : (tex ? "" : "[");
    for (unsigned c = 0; c < J.cols(); ++c)
      out += (c ? (tex ? " & " : ", ") : "") + render(J(r, c));
    out += tex ? "" : "]";
  }
  return out + (tex ? " \\end{pmatrix}" : "]");
}

/// Every expression the printers write, in the order they write them.
std::vector<GiNaC::ex> printed_expressions(const ManipulatorForm& f) {
  const size_t n = f.eq->nv;
  std::vector<GiNaC::ex> all;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i; j < n; ++j) all.push_back(f.D(i, j));
  for (const Christoffel& c : f.christoffel) all.push_back(c.value);
  for (size_t k = 0; k < n; ++k)
    for (size_t j = 0; j < n; ++j) all.push_back(f.C(k, j));
  all.insert(all.end(), f.g.begin(), f.g.end());
  for (const LinkJacobian& J : f.jacobians)
    for (const GiNaC::matrix* m : {&J.Jv, &J.Jw})
      for (unsigned r = 0; r < m->rows(); ++r)
        for (unsigned c = 0; c < m->cols(); ++c) all.push_back((*m)(r, c));
  all.insert(all.end(), f.tau.begin(), f.tau.end());
  return all;
}

/// The form through the named common subexpressions of one tape computing every printed
/// expression (docs/theory.md §8): the text grows with the tape, not with the expansion.
struct SharedForm {
  Tape::Text text;
  tape_detail::ExMap<size_t> output_of;  ///< expression → its output in `text`

  explicit SharedForm(const ManipulatorForm& f) {
    const std::vector<GiNaC::ex> all = printed_expressions(f);
    const std::vector<GiNaC::symbol> in = f.eq->tape_inputs();
    std::vector<std::string> names;
    for (const GiNaC::symbol& s : in) names.push_back(s.get_name());
    text = Tape::compile(all, in).to_text(names, "m");
    for (size_t i = 0; i < all.size(); ++i) output_of.emplace(all[i], i);
  }
  std::string operator()(const GiNaC::ex& e) const { return text.outputs.at(output_of.at(e)); }
};

std::string format_text(const ManipulatorForm& f, Style style, const SharedForm* shared) {
  const Equations& eq = *f.eq;
  const size_t n = eq.nv;
  const bool tex = style == Style::Latex && !shared;  // the shared form is plain text
  const Render render = [&](const GiNaC::ex& e) {
    return shared ? (*shared)(e) : str(e, tex ? Style::Latex : Style::Text);
  };
  io::EquationWriter out(tex ? Style::Latex : Style::Text);
  const io::LineSink line = out.line_sink();
  const io::HeadingSink heading = out.heading_sink();
  std::string coords;
  for (size_t i = 0; i < n; ++i) coords += (i ? ", " : "") + eq.kin.q_names[i];
  out.raw(
      fmt::format("{}{} — manipulator form D(q) q_ddot + C(q, q_dot) q_dot + g(q) = tau, q = "
                  "({})\n",
                  tex ? "% " : "", eq.model->name, coords));
  if (shared) {
    out.raw(fmt::format(
        "Large model: written out in full, D, the Christoffel symbols, g and the link Jacobians\n"
        "have more than {} expression nodes, so they are printed through {} named common\n"
        "subexpressions (m1 …, each defined before it is used); `lagrange derive --form "
        "manipulator --expand` prints the full expansion.\n",
        kFullExpansionLimit, shared->text.definitions.size()));
    heading("Common subexpressions");
    for (const auto& [name, expr] : shared->text.definitions) line(name, expr);
  }
  heading("Inertia matrix D(q)");
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i; j < n; ++j)
      line(fmt::format("d_{{{}}}", indices(n, {i, j})), render(f.D(i, j)));
  heading(tex ? "Christoffel symbols (non-zero)"
              : "Christoffel symbols c_ijk = 1/2 (d d_kj/d q_i + d d_ki/d q_j - d d_ij/d q_k), "
                "non-zero");
  if (f.christoffel.empty()) out.raw(tex ? "  % none\n" : "  (none)\n");
  for (const Christoffel& c : f.christoffel)
    line(fmt::format("c_{{{}}}", indices(n, {c.i, c.j, c.k})), render(c.value));
  heading(tex ? "C(q, \\dot q)" : "C(q, q_dot), C_kj = sum_i c_ijk q_dot_i");
  for (size_t k = 0; k < n; ++k)
    for (size_t j = 0; j < n; ++j)
      if (!f.C(k, j).is_zero())
        line(fmt::format("C_{{{}}}", indices(n, {k, j})), render(f.C(k, j)));
  heading(tex ? "g(q)" : "Gravity g(q) = dP/dq");
  for (size_t k = 0; k < n; ++k) line(fmt::format("g_{{{}}}", k + 1), render(f.g[k]));
  if (!f.jacobians.empty())
    heading(tex ? "Link Jacobians: v_c = J_v \\dot q, \\omega = J_\\omega \\dot q (world axes)"
                : "Link Jacobians: centre-of-mass velocity v_c = J_v q_dot, angular velocity "
                  "omega = J_w q_dot (world axes)");
  const Style jstyle = tex ? Style::Latex : Style::Text;
  for (const LinkJacobian& J : f.jacobians) {
    const std::string link = tex ? "\\mathrm{" + io::latex_escape(J.link) + "}" : J.link;
    line(tex ? "J_{v," + link + "}" : "J_v(" + link + ")", matrix_str(J.Jv, jstyle, render));
    line(tex ? "J_{\\omega," + link + "}" : "J_w(" + link + ")", matrix_str(J.Jw, jstyle, render));
  }
  heading(tex ? "\\tau" : "Joint forces tau (generalised forces)");
  for (size_t k = 0; k < n; ++k) line(fmt::format("tau_{{{}}}", k + 1), render(f.tau[k]));
  const std::string text = out.finish();
  if (!shared || style != Style::Latex) return text;
  return "% " + eq.model->name + ": large model, printed as plain text through common " +
         "subexpressions (--expand for LaTeX of the full expansion)\n\\begin{verbatim}\n" + text +
         "\\end{verbatim}\n";
}

std::string format_json(const ManipulatorForm& f, const SharedForm* shared) {
  const Equations& eq = *f.eq;
  const size_t n = eq.nv;
  auto s = [&](const GiNaC::ex& e) { return shared ? (*shared)(e) : str(e, Style::Text); };
  // LaTeX of the full expressions only: the shared form's are names of subexpressions.
  auto latex = [&](const GiNaC::ex& e) { return shared ? s(e) : str(e, Style::Latex); };
  nlohmann::json j;
  j["name"] = eq.model->name;
  j["form"] = "manipulator";
  for (const auto& c : eq.kin.q_names) j["coordinates"].push_back(c);
  if (shared) {
    j["subexpressions"] = nlohmann::json::array();
    for (const auto& [name, expr] : shared->text.definitions)
      j["subexpressions"].push_back({name, expr});
  }
  for (size_t i = 0; i < n; ++i) {
    nlohmann::json d = nlohmann::json::array(), c = nlohmann::json::array();
    for (size_t k = 0; k < n; ++k) {
      d.push_back(s(i <= k ? f.D(i, k) : f.D(k, i)));
      c.push_back(s(f.C(i, k)));
    }
    j["D"].push_back(d);
    j["C"].push_back(c);
    j["g"].push_back(s(f.g[i]));
    j["tau"].push_back(s(f.tau[i]));
    j["latex"]["g"].push_back(latex(f.g[i]));
  }
  j["christoffel"] = nlohmann::json::array();
  for (const Christoffel& c : f.christoffel)
    j["christoffel"].push_back({{"i", c.i + 1},
                                {"j", c.j + 1},
                                {"k", c.k + 1},
                                {"value", s(c.value)},
                                {"latex", latex(c.value)}});
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

std::string format_manipulator(const ManipulatorForm& form, const std::string& format,
                               bool expand) {
  if (format != "text" && format != "latex" && format != "json")
    throw std::invalid_argument("unknown format '" + format + "'; expected text, latex or json");
  std::optional<SharedForm> shared;
  if (!expand &&
      io::tree_size(printed_expressions(form), kFullExpansionLimit + 1) > kFullExpansionLimit)
    shared.emplace(form);
  const SharedForm* s = shared ? &*shared : nullptr;
  if (format == "json") return format_json(form, s);
  return format_text(form, format == "latex" ? Style::Latex : Style::Text, s);
}

}  // namespace lagrange
