#pragma once
// Expressions as text or LaTeX for the equation printers (src/io/equations_format.cpp,
// body_equations.cpp).

#include <ginac/ginac.h>

#include <functional>
#include <string>
#include <vector>

#include "lagrange/equations.hpp"

namespace lagrange::io {

/// Plain text or LaTeX.
enum class Style { Text, Latex };

/// A small expression in its shortest form among as-derived, expanded and simplified.
std::string str(const GiNaC::ex& e, Style style);
/// A symbol's name (its LaTeX name in Latex style).
std::string symbol_str(const GiNaC::symbol& s, Style style);
/// Underscores escaped for \mathrm{}.
std::string latex_escape(const std::string& name);
/// The multiplier of a named constraint: lambda_name or \lambda_{\mathrm{name}}.
std::string multiplier_str(const std::string& constraint, Style style);

/// Expression-tree nodes of `exprs` written out in full (shared subexpressions counted at every
/// use), saturating at `cap`; linear in the size of their DAG.
size_t tree_size(const std::vector<GiNaC::ex>& exprs, size_t cap);
/// Size of the equations written out in full: expression-tree nodes of T, U, M, h, Q, C, c and
/// Ċ with shared subexpressions counted at every use, saturating at `cap`.
size_t expanded_size(const Equations& eq, size_t cap);
/// The equations through the compiled tape's named common subexpressions (text, latex as a
/// verbatim block, or json).
std::string format_equations_cse(const Equations& eq, const std::string& format);

/// Writes a section heading.
using HeadingSink = std::function<void(const std::string&)>;
/// Writes one equation lhs = rhs.
using LineSink = std::function<void(const std::string&, const std::string&)>;

/// Equations accumulated as text (`  lhs = rhs` under headings) or LaTeX (`lhs &= rhs \\`, one
/// align* block per heading), shared by `derive`'s printers.
class EquationWriter {
 public:
  explicit EquationWriter(Style style) : tex_(style == Style::Latex) {}
  void heading(const std::string& h);
  void line(const std::string& lhs, const std::string& rhs);
  /// Text as is (comments, notes).
  void raw(const std::string& text) { out_ += text; }
  HeadingSink heading_sink() {
    return [this](const std::string& h) { heading(h); };
  }
  LineSink line_sink() {
    return [this](const std::string& l, const std::string& r) { line(l, r); };
  }
  /// Everything written, with the last align* block closed.
  std::string finish();

 private:
  bool tex_;
  bool open_ = false;
  std::string out_;
};

/// The elements' sections (a winch's T_drum = …), their names in LaTeX as the model's symbols
/// are (T_{\mathrm{drum}}, not T_drum, whose subscript would take one letter).
void print_element_equations(const Model& model, Style style, EquationWriter& out);

/// Each rigid body's equations in the seed's form (docs/theory.md §4.4): for a free body
/// m r̈ + ∂V/∂r = F_r − (∂C/∂r)ᵀλ, J ω̇ + ω × Jω + 2P(∂V/∂R) = F_rot − 2P(∂C/∂R)ᵀλ and
/// Ṙ = R(Ω + Ξ); for a posed body its pose, ω = unskew(RᵀṘ) and its kinetic energy.
void print_body_equations(const Equations& eq, Style style, const HeadingSink& heading,
                          const LineSink& line);

}  // namespace lagrange::io
