#include "cli/initial_state.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "lagrange/compiled_model.hpp"
#include "lagrange/error.hpp"
#include "lagrange/tape.hpp"
#include "symbolic/expansion_bound.hpp"

namespace lagrange::cli {

namespace {

/// At most this many unmet constraints are listed by name.
constexpr size_t kListed = 5;

// "'rod': C = 0.085 (0.085 at the start)" for each constraint still violated after projection.
std::string unmet_constraints(const CompiledModel& cm, const InitialConsistency& ic, double tol,
                              std::vector<size_t>& rows) {
  std::string text;
  for (size_t r = 0; r < cm.m; ++r) {
    const bool c = std::abs(ic.C[r]) > tol, rate = std::abs(ic.Cdot[r]) > tol;
    if (!c && !rate) continue;
    rows.push_back(r);
    if (rows.size() > kListed) continue;
    std::string what;
    if (c) what = fmt::format("C = {:.3g} ({:.3g} at the start)", ic.C[r], ic.C0[r]);
    if (rate)
      what +=
          fmt::format("{}Ċ = {:.3g} ({:.3g} at the start)", c ? ", " : "", ic.Cdot[r], ic.Cdot0[r]);
    text += fmt::format("{}'{}': {}", text.empty() ? "" : "; ", cm.constraint_names[r], what);
  }
  if (rows.size() > kListed) text += fmt::format("; and {} more", rows.size() - kListed);
  return text;
}

// "x = 0.9, y = -0.6": the fixed coordinates the unmet constraints depend on (all fixed ones when
// the constraints' pattern names none of them).
std::string fixed_in_the_way(const CompiledModel& cm, const std::vector<size_t>& rows,
                             const std::vector<double>& q) {
  std::vector<bool> in_way(cm.nq, false);
  for (const auto& [row, col] : cm.Cq_pattern)
    if (cm.fixed[col] && std::find(rows.begin(), rows.end(), row) != rows.end()) in_way[col] = true;
  if (std::find(in_way.begin(), in_way.end(), true) == in_way.end()) in_way = cm.fixed;
  std::string text;
  for (size_t i = 0; i < cm.nq; ++i)
    if (in_way[i])
      text += fmt::format("{}{} = {:.6g}", text.empty() ? "" : ", ", cm.coordinate_names[i], q[i]);
  return text;
}

// The parameters `e` depends on, through the named intermediates `defs` (each visited once).
std::string parameters_in(const Model& model, const std::vector<double>& values, const GiNaC::ex& e,
                          const std::vector<Tape::Definition>& defs) {
  GiNaC::exmap defined;
  for (const auto& [symbol, value] : defs) defined[symbol] = value;
  std::vector<bool> used(model.parameters.size(), false);
  GiNaC::exset seen;
  std::vector<GiNaC::ex> pending{e};
  while (!pending.empty()) {
    const GiNaC::ex x = pending.back();
    pending.pop_back();
    if (!seen.insert(x).second) continue;
    if (GiNaC::is_a<GiNaC::symbol>(x)) {
      if (const auto it = defined.find(x); it != defined.end()) pending.push_back(it->second);
      for (size_t j = 0; j < model.parameters.size(); ++j)
        if (x.is_equal(model.parameters[j].sym)) used[j] = true;
      continue;
    }
    for (size_t k = 0; k < x.nops(); ++k) pending.push_back(x.op(k));
  }
  std::string text;
  for (size_t j = 0; j < used.size(); ++j)
    if (used[j])
      text +=
          fmt::format("{}{} = {:g}", text.empty() ? "" : ", ", model.parameters[j].name, values[j]);
  return text;
}

// A damper whose points coincide at the start: its force −c ḋ acts along b − a, and
// ḋ = (b − a)·(ḃ − ȧ)/|b − a| is 0/0 there (docs/theory.md §4.2). Named at the damper.
void require_dampers_apart(const Model& model, const GiNaC::exmap& at_start) {
  for (const Damper& d : model.dampers) {
    const Point* a = model.find_point(d.a);
    const Point* b = model.find_point(d.b);
    if (!a || !b) continue;
    GiNaC::ex length2 = 0;
    for (size_t k = 0; k < 3; ++k) length2 += GiNaC::pow(b->pos[k] - a->pos[k], 2);
    GiNaC::ex value;
    try {
      value = GiNaC::evalf(length2.subs(at_start));
    } catch (const std::exception&) {
      continue;  // the dynamics' own message says more
    }
    if (GiNaC::is_a<GiNaC::numeric>(value) && GiNaC::ex_to<GiNaC::numeric>(value).is_zero())
      throw ModelError(d.loc, fmt::format("the damper between '{}' and '{}' has length 0 at the "
                                          "initial state: its force acts along the line between "
                                          "its points, which has no direction there; expected "
                                          "its points apart at the start",
                                          d.a, d.b));
  }
}

}  // namespace

InitialConsistency require_consistent_initial_state(const Model& model, Dynamics& dyn,
                                                    std::vector<double>& q,
                                                    std::vector<double>& v) {
  const CompiledModel& cm = dyn.model();
  const std::vector<double> q_start = q;
  const SimulationOptions defaults;
  const double tol = defaults.projection_tol;
  InitialConsistency ic = make_initial_state_consistent(dyn, 0.0, q, v, tol);
  if (ic.consistent) return ic;
  std::vector<size_t> rows;
  const std::string unmet = unmet_constraints(cm, ic, tol, rows);
  const std::string why =
      ic.blocked_by_fixed
          ? fmt::format(
                "the coordinates marked 'fixed: true' stand in the way: {} (without "
                "'fixed' the projection reaches C = 0 and Ċ = 0)",
                fixed_in_the_way(cm, rows, q_start))
          : "no change of the coordinates not marked fixed reaches C = 0 and Ċ = 0 (the "
            "least-squares projection stops at a minimum of |C| that is not 0); expected "
            "constraints that the initial values can satisfy";
  const SourceLoc where =
      rows.empty() ? SourceLoc{model.file, 1, 1} : model.constraints[rows[0]].loc;
  throw ModelError(where, fmt::format("the initial state cannot be made consistent: constraint{} "
                                      "{} after projection; {}",
                                      rows.size() == 1 ? "" : "s", unmet, why));
}

// A mass matrix that is singular at the start is reported at the coordinate without inertia,
// with its mass-matrix entry and the parameters that entry depends on.
void require_regular_initial_state(const Model& model, const Equations& eq, Dynamics& dyn,
                                   const std::vector<double>& q, const std::vector<double>& v) {
  const CompiledModel& cm = dyn.model();
  std::vector<double> qdot(cm.nq), a(cm.nv), lambda(cm.m);
  try {
    dyn.forward(0.0, q.data(), v.data(), qdot.data(), a.data(), lambda.data());
  } catch (const SimulationError& e) {
    if (eq.recursive) require_positive_pivots(model, eq, dyn);
    // CLN refuses subnormal doubles (floating_point_underflow_exception): flush them to 0.
    auto number = [](double x) { return GiNaC::numeric(std::isnormal(x) ? x : 0.0); };
    GiNaC::exmap at_start;
    for (size_t i = 0; i < model.coordinates.size(); ++i) {
      at_start[model.coordinates[i].q] = number(q[i]);
      at_start[model.coordinates[i].v] = number(v[i]);
    }
    at_start[model.t] = 0;
    for (size_t j = 0; j < model.parameters.size(); ++j)
      at_start[model.parameters[j].sym] = number(dyn.parameters()[j]);
    require_dampers_apart(model, at_start);
    for (size_t i = 0; i < cm.plain; ++i) {
      const GiNaC::ex Mii = eq.M(static_cast<unsigned>(i), static_cast<unsigned>(i));
      GiNaC::ex value;
      try {
        value = GiNaC::evalf(Mii.subs(at_start));
      } catch (const std::exception&) {
        continue;  // a pole of M at the initial state: reported below with the dynamics' message
      }
      if (!GiNaC::is_a<GiNaC::numeric>(value) ||
          std::abs(GiNaC::ex_to<GiNaC::numeric>(value).to_double()) > 1e-300)
        continue;
      std::string depends;
      for (size_t j = 0; j < model.parameters.size(); ++j)
        if (Mii.has(model.parameters[j].sym))
          depends += fmt::format("{}{} = {:g}", depends.empty() ? "" : ", ",
                                 model.parameters[j].name, dyn.parameters()[j]);
      const Coordinate& c = model.coordinates[i];
      std::ostringstream entry;
      entry << symbolic::simplify_within(Mii, 2000);  // an error message: bounded algebra only
      throw ModelError(c.loc,
                       fmt::format("coordinate '{}' has no inertia at the initial state: the mass "
                                   "matrix entry M[{},{}] = {} is 0{}; expected positive masses "
                                   "and non-zero lengths",
                                   c.name, c.name, c.name, entry.str(),
                                   depends.empty() ? "" : " with " + depends));
    }
    const SourceLoc where =
        model.coordinates.empty() ? SourceLoc{model.file, 1, 1} : model.coordinates[0].loc;
    throw ModelError(
        where, fmt::format("the dynamics cannot be evaluated at the initial state: {}", e.what()));
  }
}

// docs/theory.md §4.9, Pivots: the articulated-body algorithm eliminates M from the leaves, its
// pivots D are those of that elimination, and M is positive definite exactly when all are
// positive.
void require_positive_pivots(const Model& model, const Equations& eq, const Dynamics& dyn) {
  const Tape tape = Tape::compile(eq.pivots, eq.tape_inputs(), eq.definitions);
  std::vector<double> D(tape.num_outputs()), work(tape.work_size());
  tape.eval(dyn.last_inputs().data(), D.data(), work.data());
  double scale = 0;
  for (const double d : D)
    if (std::isfinite(d)) scale = std::max(scale, std::abs(d));
  // The elimination's first failing pivot is a number; the pivots eliminated after it divide
  // by it and are not.
  const auto failing = [&](bool finite) {
    return std::find_if(D.begin(), D.end(), [&](double d) {
      return !(d > 1e-13 * scale) && static_cast<bool>(std::isfinite(d)) == finite;
    });
  };
  auto bad = failing(true);
  if (bad == D.end()) bad = failing(false);
  if (bad != D.end()) {
    const auto i = static_cast<size_t>(bad - D.begin());
    const Coordinate& c = model.coordinates[i];
    const std::string depends =
        parameters_in(model, dyn.parameters(), eq.pivots[i], eq.definitions);
    throw ModelError(
        c.loc,
        fmt::format("coordinate '{}' has {} inertia at the initial state: the articulated-body "
                    "pivot D of its joint (the inertia about it of the links it carries) is "
                    "{:.6g}{}{}; expected positive masses and non-zero lengths",
                    c.name, D[i] < 0 ? "a negative" : "no", D[i],
                    D[i] < 0 ? ", so the mass matrix is indefinite" : "",
                    depends.empty() ? "" : " with " + depends));
  }
}

}  // namespace lagrange::cli
