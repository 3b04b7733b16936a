#include "io/equation_text.hpp"

#include <fmt/format.h>

#include <sstream>
#include <vector>

#include "model/latex_names.hpp"
#include "symbolic/expansion_bound.hpp"
#include "symbolic/printed_size.hpp"

namespace lagrange::io {

namespace {

// Small expressions are shown in their shortest form among: as derived, expanded, and
// simplified with sin² + cos² = 1 (lagrange::simplify); only those whose expansion, and for
// the simplified form whose common denominator (normal()), is bounded.
GiNaC::ex tidy(const GiNaC::ex& e) {
  using symbolic::printed_size;
  size_t best_size = printed_size(e);
  // Short text can still expand without bound ((a + b + c)^40): ask before expanding.
  constexpr size_t kTidyTerms = 400;
  if (best_size > 600 || !symbolic::expands_within(e, kTidyTerms)) return e;
  GiNaC::ex best = e;
  const GiNaC::ex simplified = symbolic::simplify_within(e, kTidyTerms);
  std::vector<GiNaC::ex> candidates{e.expand(), simplified};
  // The simplified form is bounded on its own terms: its expansion is asked about too.
  if (symbolic::expands_within(simplified, kTidyTerms)) candidates.push_back(simplified.expand());
  for (const GiNaC::ex& c : candidates) {
    const size_t size = printed_size(c);
    if (size < best_size) {
      best = c;
      best_size = size;
    }
  }
  return best;
}

}  // namespace

std::string str(const GiNaC::ex& e, Style style) {
  std::ostringstream os;
  if (style == Style::Latex) os << GiNaC::latex;
  os << tidy(e);
  return os.str();
}

std::string symbol_str(const GiNaC::symbol& s, Style style) {
  std::ostringstream os;
  if (style == Style::Latex) os << GiNaC::latex;
  os << s;
  return os.str();
}

std::string latex_escape(const std::string& name) {
  std::string r;
  for (char c : name) r += c == '_' ? std::string("\\_") : std::string(1, c);
  return r;
}

std::string multiplier_str(const std::string& constraint, Style style) {
  return style == Style::Latex ? "\\lambda_{\\mathrm{" + latex_escape(constraint) + "}}"
                               : "lambda_" + constraint;
}

void print_element_equations(const Model& model, Style style, EquationWriter& out) {
  const bool tex = style == Style::Latex;
  for (const ElementSummary& s : model.element_summaries) {
    out.heading(s.title);
    for (const auto& note : s.notes) out.raw(tex ? "% " + note + "\n" : "  " + note + "\n");
    for (const auto& [lhs, rhs] : s.equations)
      out.line(tex ? lagrange::model::latex_name(lhs) : lhs, str(rhs, style));
  }
}

void EquationWriter::heading(const std::string& h) {
  if (!tex_) {
    out_ += fmt::format("\n{}\n", h);
    return;
  }
  out_ += fmt::format("{}% {}\n\\begin{{align*}}\n", open_ ? "\\end{align*}\n" : "", h);
  open_ = true;
}

void EquationWriter::line(const std::string& lhs, const std::string& rhs) {
  out_ += tex_ ? fmt::format("  {} &= {} \\\\\n", lhs, rhs) : fmt::format("  {} = {}\n", lhs, rhs);
}

std::string EquationWriter::finish() {
  if (tex_ && open_) out_ += "\\end{align*}\n";
  open_ = false;
  return out_;
}

}  // namespace lagrange::io
