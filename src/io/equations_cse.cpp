// `lagrange derive` of large models: the equations printed through the named common
// subexpressions of the compiled tape (docs/theory.md §8), so that the output grows with the
// tape instead of with the full expansion (259 MB of text for the 200-link pendulum).

#include <fmt/format.h>

#include <nlohmann/json.hpp>
#include <unordered_map>

#include "io/equation_text.hpp"
#include "lagrange/compiled_model.hpp"
#include "lagrange/io.hpp"

namespace lagrange::io {

namespace {

struct Hash {
  size_t operator()(const GiNaC::ex& e) const { return e.gethash(); }
};
struct Equal {
  bool operator()(const GiNaC::ex& a, const GiNaC::ex& b) const { return a.is_equal(b); }
};
using SizeMemo = std::unordered_map<GiNaC::ex, size_t, Hash, Equal>;

// Nodes of e written out as a tree (shared subexpressions counted at every use), saturating
// at `cap`; linear in the size of the expression DAG thanks to the memo.
size_t tree_size(const GiNaC::ex& e, SizeMemo& memo, size_t cap) {
  if (e.nops() == 0) return 1;
  if (const auto it = memo.find(e); it != memo.end()) return it->second;
  size_t n = 1;
  for (size_t i = 0; i < e.nops() && n < cap; ++i) n += tree_size(e.op(i), memo, cap);
  n = std::min(n, cap);
  memo.emplace(e, n);
  return n;
}

// Input names of the tapes: t, q, v, u, u_dot, u_ddot, p (CompiledModel::input_count()).
std::vector<std::string> input_names(const CompiledModel& cm) {
  std::vector<std::string> names{"t"};
  names.insert(names.end(), cm.coordinate_names.begin(), cm.coordinate_names.end());
  names.insert(names.end(), cm.velocity_names.begin(), cm.velocity_names.end());
  for (const char* suffix : {"", "_dot", "_ddot"})
    for (const auto& u : cm.input_names) names.push_back(u + suffix);
  names.insert(names.end(), cm.parameter_names.begin(), cm.parameter_names.end());
  return names;
}

// The dynamics tape's outputs under the names the full form uses (M_{i,j}, (h+Q)_{q}, …), by
// section; q̇ of plain coordinates (= v) and ∂C/∂q (the projection's copy of G) are left out.
struct Section {
  std::string heading;
  std::vector<std::pair<std::string, std::string>> lines;
};

std::vector<Section> dynamics_sections(const CompiledModel& cm, const Tape::Text& text) {
  const auto& out = text.outputs;
  auto vname = [&](size_t i) {
    return i < cm.plain ? cm.coordinate_names[i] : cm.velocity_names[i];
  };
  std::vector<Section> s;
  s.push_back({"Mass matrix M(q) (lower triangle)", {}});
  for (size_t e = 0; e < cm.M_pattern.size(); ++e)
    s.back().lines.emplace_back(
        fmt::format("M_{{{},{}}}", cm.M_pattern[e].first + 1, cm.M_pattern[e].second + 1), out[e]);
  s.push_back({"Forcing h(q, v) + Q", {}});
  for (size_t i = 0; i < cm.nv; ++i)
    s.back().lines.emplace_back(fmt::format("(h+Q)_{{{}}}", vname(i)), out[cm.rhs_out() + i]);
  if (cm.nq > cm.plain) {
    s.push_back({"Kinematics q_dot = K(q) v (free bodies, with the drift correction)", {}});
    for (size_t i = cm.plain; i < cm.nq; ++i)
      s.back().lines.emplace_back("d/dt " + cm.coordinate_names[i], out[cm.qdot_out() + i]);
  }
  if (cm.m == 0) return s;
  const auto& cn = cm.constraint_names;
  s.push_back({"Constraints (index-3 DAE: C = 0)", {}});
  for (size_t r = 0; r < cm.m; ++r)
    s.back().lines.emplace_back("C_{" + cn[r] + "}", out[cm.C_out() + r]);
  s.push_back({"Constraint Jacobian G = dC/dq", {}});
  for (size_t e = 0; e < cm.G_pattern.size(); ++e)
    s.back().lines.emplace_back(
        fmt::format("G_{{{},{}}}", cn[cm.G_pattern[e].first], vname(cm.G_pattern[e].second)),
        out[cm.G_out() + e]);
  s.push_back({"Index-1 form (C'' = G a + c = 0) and Baumgarte rates", {}});
  for (size_t r = 0; r < cm.m; ++r) {
    s.back().lines.emplace_back("c_{" + cn[r] + "}", out[cm.c_out() + r]);
    s.back().lines.emplace_back("Cdot_{" + cn[r] + "}", out[cm.Cdot_out() + r]);
  }
  return s;
}

std::string format_text_cse(const Equations& eq, const CompiledModel& cm,
                            const Tape::Text& energies, const Tape::Text& dyn) {
  std::string out =
      fmt::format("{} — {} coordinates, {} constraints\n", eq.model->name, eq.nq, eq.m);
  out += fmt::format(
      "Large model: written out in full, these equations have more than {} expression nodes,\n"
      "so they are printed through the {} named common subexpressions of the compiled tape\n"
      "(e1 … for the energies, x1 … for the dynamics, each defined before it is used);\n"
      "`lagrange derive --expand` prints the full expansion.\n",
      kFullExpansionLimit, energies.definitions.size() + dyn.definitions.size());
  out += "Equations of motion: M(q) a = h(q, v) + Q - G^T lambda\n";
  auto line = [&](const std::string& lhs, const std::string& rhs) {
    out += fmt::format("  {} = {}\n", lhs, rhs);
  };
  out += "\nEnergies\n";
  for (const auto& [name, expr] : energies.definitions) line(name, expr);
  line("T", energies.outputs[0]);
  line("U", energies.outputs[1]);
  for (const ElementSummary& s : eq.model->element_summaries) {  // one segment's terms each
    out += "\n" + s.title + "\n";
    for (const auto& note : s.notes) out += "  " + note + "\n";
    for (const auto& [lhs, rhs] : s.equations) line(lhs, str(rhs, Style::Text));
  }
  out += fmt::format("\nCommon subexpressions of the dynamics ({})\n", dyn.definitions.size());
  for (const auto& [name, expr] : dyn.definitions) line(name, expr);
  for (const Section& s : dynamics_sections(cm, dyn)) {
    out += "\n" + s.heading + "\n";
    for (const auto& [lhs, rhs] : s.lines) line(lhs, rhs);
  }
  return out;
}

std::string format_json_cse(const Equations& eq, const CompiledModel& cm,
                            const Tape::Text& energies, const Tape::Text& dyn) {
  nlohmann::json j;
  j["name"] = eq.model->name;
  j["form"] = "common_subexpressions";
  for (const auto& c : cm.coordinate_names) j["coordinates"].push_back(c);
  for (const auto& c : cm.velocity_names) j["velocities"].push_back(c);
  for (const auto& [name, expr] : energies.definitions) j["energy_subexpressions"][name] = expr;
  j["T"] = energies.outputs[0];
  j["U"] = energies.outputs[1];
  j["subexpressions"] = nlohmann::json::array();
  for (const auto& [name, expr] : dyn.definitions) j["subexpressions"].push_back({name, expr});
  for (const Section& s : dynamics_sections(cm, dyn))
    for (const auto& [lhs, rhs] : s.lines) j["equations"][lhs] = rhs;
  return j.dump(2) + "\n";
}

}  // namespace

size_t tree_size(const std::vector<GiNaC::ex>& exprs, size_t cap) {
  SizeMemo memo;
  size_t n = 0;
  for (const GiNaC::ex& e : exprs)
    if (n < cap) n = std::min(cap, n + tree_size(e, memo, cap));
  return n;
}

size_t expanded_size(const Equations& eq, size_t cap) {
  std::vector<GiNaC::ex> all;
  auto add = [&](const GiNaC::ex& e) { all.push_back(e); };
  add(eq.T);
  add(eq.U);
  for (size_t i = 0; i < eq.nv; ++i) {
    for (size_t k = 0; k <= i; ++k) add(eq.M(i, k));
    add(eq.h[i]);
    add(eq.Q[i]);
  }
  for (size_t r = 0; r < eq.m; ++r) {
    add(eq.C[r]);
    add(eq.c[r]);
    add(eq.Cdot[r]);
  }
  return tree_size(all, cap);
}

std::string format_equations_cse(const Equations& eq, const std::string& format) {
  const auto cm = compile(eq);
  const std::vector<std::string> names = input_names(*cm);
  const Tape::Text energies = cm->observables.to_text(names, "e");
  const Tape::Text dyn = cm->dynamics.to_text(names, "x");
  if (format == "json") return format_json_cse(eq, *cm, energies, dyn);
  const std::string text = format_text_cse(eq, *cm, energies, dyn);
  if (format == "text") return text;
  return "% " + eq.model->name + ": large model, printed as plain text through common " +
         "subexpressions (lagrange derive --expand for LaTeX of the full expansion)\n" +
         "\\begin{verbatim}\n" + text + "\\end{verbatim}\n";
}

}  // namespace lagrange::io
