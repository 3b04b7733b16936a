#include "optimize/transcription.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>

#include "analysis/off_kink.hpp"
#include "optimize/file_guess.hpp"
#include "optimize/simulated_guess.hpp"

namespace lagrange::collocation {

namespace {

std::vector<size_t> control_input_indices(const OptimalControlSpec& spec) {
  std::vector<size_t> c;
  for (const ControlSpec& s : spec.controls) c.push_back(s.input);
  return c;
}

std::vector<GiNaC::ex> guessed_paths(const OptimalControlSpec& spec) {
  std::vector<GiNaC::ex> fs;
  for (const auto& [state, path] : spec.guess_paths) fs.push_back(path);
  return fs;
}

/// Per coordinate, whether a projection keeps it (Dynamics::try_project's flags, which hold a
/// coordinate and its rate together): kept when either is in `keep` (nq + nv flags). The plain
/// coordinates come first in q and v; each free body has 12 components in q and 6 in v, so they
/// number nv − (nq − nv). A body's rates have no flag of their own.
std::vector<bool> kept_coordinates(const std::vector<bool>& keep, size_t nq) {
  std::vector<bool> flags(keep.begin(), keep.begin() + static_cast<long>(nq));
  const size_t nv = keep.size() - nq, plain = nv - (nq - nv);
  for (size_t i = 0; i < plain; ++i) flags[i] = flags[i] || keep[nq + i];
  return flags;
}

/// Index in x = (q, v) of a state reference: a plain coordinate's q index is its v index; a free
/// body's component is found by its state name.
size_t state_index(const StateRef& s, const CompiledModel& c) {
  if (s.body_state.empty()) return s.velocity ? c.nq + s.coordinate : s.coordinate;
  const std::vector<std::string>& names = s.velocity ? c.velocity_names : c.coordinate_names;
  const auto it = std::find(names.begin(), names.end(), s.body_state);
  if (it == names.end())
    throw std::invalid_argument("the compiled model has no state '" + s.body_state + "'");
  return (s.velocity ? c.nq : 0) + static_cast<size_t>(it - names.begin());
}

}  // namespace

Transcription::Transcription(const Equations& eq, std::shared_ptr<const CompiledModel> cm,
                             Dynamics& dyn, const OptimalControlSpec& spec, int intervals,
                             int degree, const std::vector<double>& q0,
                             const std::vector<double>& v0, HessianChoice hessian,
                             const StageStart* stage, Evaluation evaluation,
                             const MachineCodeOptions& machine_code)
    : eq_(eq),
      cm_(cm),
      dyn_(dyn),
      spec_(spec),
      fun_(eq, *cm, problem_functions(spec), control_input_indices(spec), spec.multipliers),
      dae_(stage != nullptr && stage->residual
               ? stage->residual
               : std::make_shared<const PointResidual>(eq, *cm, control_input_indices(spec),
                                                       evaluation, machine_code)),
      invariant_jac_(eq, *cm),
      rad_(radau(degree)),
      N_(intervals),
      d_(degree),
      nq_(cm->nq),
      nv_(cm->nv),
      nx_(cm->nq + cm->nv),
      m_(cm->m),
      nu_(spec.controls.size()),
      np_(spec.path.size()),
      free_T_(spec.free_horizon.has_value()),
      T_(spec.horizon),
      sign_(spec.maximize ? -1.0 : 1.0),
      paths_(eq, *cm, guessed_paths(spec), {}),
      q0_(q0),
      v0_(v0) {
  if (intervals < 1) throw std::invalid_argument("expected at least 1 collocation interval");
  if (spec.multipliers.size() != m_)
    throw std::invalid_argument("the problem's multipliers do not match the model's constraints");
  for (const ControlSpec& c : spec.controls) {
    if (c.constant && c.polynomial)
      throw std::invalid_argument(fmt::format("control '{}' cannot be both constant and polynomial",
                                              eq.model->inputs[c.input].name));
    controls_.push_back(c.input);
    polynomial_.push_back(c.polynomial);
  }
  if (free_T_) {
    // dt/dT enters every point: the dynamics must not depend on t itself (∂/∂t is not on the tape).
    const GiNaC::symbol& t = eq.model->t;
    bool timed = false;
    for (const GiNaC::ex& e : dynamics_expressions(eq, *cm)) timed = timed || e.has(t);
    for (size_t i = 0; i < eq.model->inputs.size(); ++i)
      if (std::find(controls_.begin(), controls_.end(), i) == controls_.end())
        timed = timed || eq.model->inputs[i].expr.has(t);
    if (timed)
      throw std::invalid_argument(
          "a free horizon needs dynamics that do not depend on t explicitly (through an input's "
          "expression or the equations); fix the horizon or make that input a control");
  }
  in_.assign(cm->input_count(), 0.0);
  xp_.assign(nx_, 0.0);
  for (size_t i = 0; i < nq_; ++i) {
    const std::string& name = cm->coordinate_names[i];
    if (name.size() > 4 && name.compare(name.size() - 4, 4, ".R11") == 0) rotations_.push_back(i);
  }
  choose_boundary_rows();
  size_t control_width = 0;  // the controls' variables per interval
  for (size_t c = 0; c < nu_; ++c) {
    u_offset_.push_back(control_width);
    control_width += static_cast<size_t>(control_points(c));
  }
  start_basis_ = point_basis(rad_, 0.0);
  block_ = static_cast<size_t>(d_) * (nx_ + m_) + control_width;
  first_ = free_T_ ? 1 : 0;
  n_ = first_ + static_cast<size_t>(N_) * block_ + nx_;
  path_rows_ = static_cast<size_t>(N_ * d_) * (nx_ + m_);
  for (size_t c = 0; c < nu_; ++c)
    if (spec.controls[c].constant) constant_.push_back(c);
  rows_ = path_rows_ + static_cast<size_t>(N_ * d_) * np_ + start_rows_.size() + periodic_.size() +
          constant_.size() * static_cast<size_t>(N_ - 1) + turning_.size();
  // The Jacobian's pattern: one walk at the starting point, entries merged by position.
  const bool warm = stage != nullptr && stage->x != nullptr;
  if (warm && stage->x->size() != n_)
    throw std::invalid_argument(fmt::format(
        "a starting point of {} values for a problem of {} variables", stage->x->size(), n_));
  guess_ = warm ? *stage->x : make_guess();
  const double track = stage != nullptr ? stage->track : 0.0;
  if (track > 0) {
    track_scale_.assign(nx_, 1.0);
    for_each_node([&](size_t at) {
      for (size_t i = 0; i < nx_; ++i)
        track_scale_[i] = std::max(track_scale_[i], std::fabs(guess_[at + i]));
    });
    for (double& s : track_scale_) s = 1.0 / (s * s);
    track_ = track / static_cast<double>(N_ * d_ + 1);
  }
  const std::vector<double>& x0 = guess_;
  std::map<std::pair<size_t, size_t>, size_t> where;
  walk_jacobian(x0.data(), [&](size_t r, size_t c, double) {
    auto [it, added] = where.emplace(std::make_pair(r, c), nz_.size());
    if (added) nz_.emplace_back(r, c);
    slot_.push_back(it->second);
  });
  if (hessian != HessianChoice::LimitedMemory)
    prepare_hessian(hessian, stage != nullptr ? stage->dae_hessian : nullptr, evaluation,
                    machine_code);
}

size_t Transcription::xi(int k, int j) const {
  if (j == d_) return xi(k + 1, 0);
  return first_ + static_cast<size_t>(k) * block_ + static_cast<size_t>(j) * nx_;
}
size_t Transcription::li(int k, int j) const {
  return first_ + static_cast<size_t>(k) * block_ + static_cast<size_t>(d_) * nx_ +
         static_cast<size_t>(j - 1) * m_;
}
size_t Transcription::ui(int k, int j, size_t c) const {
  return first_ + static_cast<size_t>(k) * block_ + static_cast<size_t>(d_) * (nx_ + m_) +
         u_offset_[c] + (polynomial_[c] ? static_cast<size_t>(j - 1) : 0);
}

Transcription::VariableName Transcription::variable_name(size_t column, const double* x) const {
  const CompiledModel& c = *cm_;
  if (free_T_ && column == 0) return {"the horizon T", ""};
  const size_t at = column - first_, k = at / block_, in = at % block_;
  const auto state = [&](size_t i, int kk, int j) -> VariableName {
    return {fmt::format("'{}'", i < nq_ ? c.coordinate_names[i] : c.velocity_names[i - nq_]),
            fmt::format("at t = {:.6g}", time(x, kk, j))};
  };
  if (k == static_cast<size_t>(N_)) return state(in, N_, 0);
  const int K = static_cast<int>(k);
  if (in < static_cast<size_t>(d_) * nx_) return state(in % nx_, K, static_cast<int>(in / nx_));
  const size_t after = in - static_cast<size_t>(d_) * nx_;
  if (after < static_cast<size_t>(d_) * m_)
    return {fmt::format("the multiplier of '{}'", c.constraint_names[after % m_]),
            fmt::format("at t = {:.6g}", time(x, K, static_cast<int>(after / m_) + 1))};
  const size_t u = after - static_cast<size_t>(d_) * m_;
  size_t control = 0;
  while (control + 1 < nu_ && u_offset_[control + 1] <= u) ++control;
  return {fmt::format("control '{}'", eq_.model->inputs[controls_[control]].name),
          fmt::format("on interval {}", k)};
}

std::string Transcription::describe_variable(size_t column, const double* x) const {
  const VariableName n = variable_name(column, x);
  return n.where.empty() ? n.quantity : n.quantity + " " + n.where;
}

std::string Transcription::row_quantity(size_t row) const {
  const size_t first_path = path_rows_, end_path = path_rows_ + static_cast<size_t>(N_ * d_) * np_;
  if (row >= first_path && row < end_path)
    return fmt::format("path '{}'", spec_.path[(row - first_path) % np_].name);
  return "";
}

// docs/theory.md §10, "Polynomial controls": U_{k,j} at a collocation point, Σ_l ℓ̃_l(0) U_{k,l}
// at the interval's start.
const double* Transcription::control(const double* x, int k, int j) const {
  u_.resize(nu_);
  for (size_t c = 0; c < nu_; ++c) {
    if (!polynomial_[c] || j > 0) {
      u_[c] = x[ui(k, j, c)];
      continue;
    }
    u_[c] = 0.0;
    for (int l = 1; l <= d_; ++l)
      u_[c] += start_basis_[static_cast<size_t>(l - 1)] * x[ui(k, l, c)];
  }
  return u_.data();
}

size_t Transcription::point_variable(size_t column, int k, int j) const {
  const size_t cu = 1 + nx_, cl = cu + nu_;
  if (column < cu) return xi(k, j) + column - 1;
  if (column < cl) return ui(k, j, column - cu);
  return li(k, j) + column - cl;
}

// At a kink of a point function (|x| at x = 0) its derivatives are the one-sided ones there
// (docs/theory.md §10, "Kinks"); its values are those at the point.
void Transcription::eval_point(const double* x, int k, int j) {
  const double* lambda = multipliers(x, k, j);
  fun_.eval(in_, lambda, out_);
  const size_t nf = fun_.count();
  if (analysis_detail::all_finite(out_.data() + nf, out_.data() + out_.size())) return;
  const std::vector<double> values(out_.begin(), out_.begin() + static_cast<long>(nf));
  std::vector<double> in = in_;  // the inputs, to move off the kink
  analysis_detail::eval_off_kink(in.data() + cm_->q_offset(), nx_, out_.data() + nf,
                                 out_.data() + out_.size(), [&] { fun_.eval(in, lambda, out_); });
  std::copy(values.begin(), values.end(), out_.begin());
}

double Transcription::time(const double* x, int k, int j) const {
  return horizon(x) * (k + rad_.tau[static_cast<size_t>(j)]) / N_;
}

void Transcription::bounds(double* xl, double* xu, double* gl, double* gu) const {
  const double inf = 2e19;  // Ipopt's infinity (nlp_lower/upper_bound_inf 1e19)
  auto finite = [&](double v) { return std::isfinite(v) ? v : (v < 0 ? -inf : inf); };
  std::fill(xl, xl + n_, -inf);
  std::fill(xu, xu + n_, inf);
  if (free_T_) {
    xl[0] = spec_.free_horizon->lower;
    xu[0] = spec_.free_horizon->upper;
  }
  for (const StateBound& b : spec_.bounds) {
    const size_t i = state_index(b.state, *cm_);  // a name lookup for a free body: once per bound
    for_each_node([&](size_t at) {
      xl[at + i] = finite(b.bounds.lower);
      xu[at + i] = finite(b.bounds.upper);
    });
  }
  for (int k = 0; k < N_; ++k)
    for (size_t c = 0; c < nu_; ++c)
      for (int j = 1; j <= control_points(c); ++j) {
        xl[ui(k, j, c)] = finite(spec_.controls[c].bounds.lower);
        xu[ui(k, j, c)] = finite(spec_.controls[c].bounds.upper);
      }
  auto fix = [&](size_t at, const BoundaryValue& b) {
    xl[at + state_index(b.state, *cm_)] = finite(b.bounds.lower);
    xu[at + state_index(b.state, *cm_)] = finite(b.bounds.upper);
  };
  if (spec_.initial) {
    for (const BoundaryValue& b : *spec_.initial) fix(xi(0, 0), b);
  } else {
    for (size_t i = 0; i < nx_; ++i)
      xl[i + first_] = xu[i + first_] = i < nq_ ? q0_[i] : v0_[i - nq_];
  }
  for (const BoundaryValue& b : final_) fix(xi(N_, 0), b);
  std::fill(gl, gl + rows_, 0.0);
  std::fill(gu, gu + rows_, 0.0);
  for (size_t p = 0; p < static_cast<size_t>(N_ * d_); ++p)
    for (size_t i = 0; i < np_; ++i) {
      gl[path_rows_ + p * np_ + i] = finite(spec_.path[i].bounds.lower);
      gu[path_rows_ + p * np_ + i] = finite(spec_.path[i].bounds.upper);
    }
}

std::vector<double> Transcription::boundary_state(bool end) {
  std::vector<double> x(nx_);
  for (size_t i = 0; i < nx_; ++i) x[i] = i < nq_ ? q0_[i] : v0_[i - nq_];
  std::vector<bool> keep(nx_, false);
  const auto write = [&](const std::vector<BoundaryValue>& values) {
    for (const BoundaryValue& b : values)
      if (b.fixed()) {
        x[state_index(b.state, *cm_)] = b.bounds.lower;
        keep[state_index(b.state, *cm_)] = true;
      }
  };
  if (spec_.initial) write(*spec_.initial);
  if (end) write(spec_.final);
  if (m_ > 0)
    dyn_.try_project(end ? T_ : 0.0, x.data(), x.data() + nq_, kept_coordinates(keep, nq_));
  return x;
}

// docs/theory.md §10, "Constrained models": at t = 0 the fixed initial values are exact and the
// invariants C = 0, Ċ = 0 are imposed where those values leave them free; at t = T the dynamics
// keep the invariants (to the collocation's accuracy), so a final value they imply is left out,
// else the constraints' gradients would be (nearly) dependent. Rows are taken in order and kept
// when independent of those before (Gram–Schmidt), at the boundary state.
void Transcription::choose_boundary_rows() {
  final_ = spec_.final;
  if (m_ == 0 && rotations_.empty()) {  // every periodic row is independent
    for (const StateRef& s : spec_.periodic) periodic_.push_back(state_index(s, *cm_));
    return;
  }
  std::vector<std::vector<double>> basis;
  const auto independent = [&](std::vector<double> r) {
    double size = 0.0;
    for (double v : r) size = std::max(size, std::fabs(v));
    if (!(size > 0.0)) return false;
    for (int pass = 0; pass < 2; ++pass)
      for (const std::vector<double>& b : basis) {
        double dot = 0.0;
        for (size_t i = 0; i < nx_; ++i) dot += r[i] * b[i];
        for (size_t i = 0; i < nx_; ++i) r[i] -= dot * b[i];
      }
    double norm = 0.0;
    for (double v : r) norm += v * v;
    norm = std::sqrt(norm);
    if (!(norm > 1e-8 * size)) return false;
    for (double& v : r) v /= norm;
    basis.push_back(std::move(r));
    return true;
  };
  const auto unit = [&](const BoundaryValue& b) {
    std::vector<double> r(nx_, 0.0);
    r[state_index(b.state, *cm_)] = 1.0;
    return r;
  };
  const auto invariant_rows = [&](bool end) {
    std::vector<std::vector<double>> rows(invariants(), std::vector<double>(nx_, 0.0));
    const std::vector<double> X = boundary_state(end);
    invariant_gradients(end ? T_ : 0.0, X.data(),
                        [&](size_t i, size_t c, double v) { rows[i][c] += v; });
    return rows;
  };
  if (spec_.initial) {
    size_t fixed = 0;
    for (const BoundaryValue& b : *spec_.initial)
      if (b.fixed()) fixed += independent(unit(b));
    if (fixed < nx_) {
      const auto rows = invariant_rows(false);
      for (size_t i = 0; i < invariants(); ++i)
        if (independent(rows[i])) start_rows_.push_back(i);
    }
  }
  // x(T) − x(0) in a direction of the invariants is kept by the dynamics: periodic rows are taken
  // after the invariants at the start state.
  basis.clear();
  const std::vector<double> X0 = boundary_state(false);
  for (const std::vector<double>& r : invariant_rows(false)) independent(r);
  // A body whose nine R entries are all periodic turns back to R(0): the three rows
  // vee(skew(R(0)ᵀR(T))) = 0, whose gradients in R(T) span the tangent space at R(0) wherever
  // the orbit closes, unlike any three fixed entries (docs/theory.md §10, "Free bodies").
  std::vector<bool> taken(nx_, false);
  for (size_t base : rotations_) {
    size_t listed = 0;
    for (const StateRef& s : spec_.periodic) {
      const size_t i = state_index(s, *cm_);
      listed += i >= base && i < base + 9;
    }
    if (listed < 9) continue;
    std::fill(taken.begin() + static_cast<long>(base), taken.begin() + static_cast<long>(base) + 9,
              true);
    for (size_t w = 0; w < 3; ++w) {
      std::vector<double> r(nx_, 0.0);
      turning_gradient(
          X0.data(), X0.data(), base, w, [&](size_t, double) {},
          [&](size_t c, double v) { r[c] += v; });
      if (independent(r)) turning_.push_back({base, w});
    }
  }
  for (const StateRef& s : spec_.periodic) {
    std::vector<double> r(nx_, 0.0);
    const size_t i = state_index(s, *cm_);
    r[i] = 1.0;
    if (!taken[i] && independent(r)) periodic_.push_back(i);
  }
  basis.clear();
  for (const std::vector<double>& r : invariant_rows(true)) independent(r);
  final_.clear();
  for (const BoundaryValue& b : spec_.final)
    (!b.fixed() || independent(unit(b)) ? final_ : implied_).push_back(b);
}

std::vector<double> Transcription::guessed_state(double t, const std::vector<double>& start,
                                                 const std::vector<double>& end,
                                                 const std::vector<bool>& keep) {
  const double s = T_ > 0 ? t / T_ : 0.0;
  std::vector<double> x(nx_);
  for (size_t i = 0; i < nx_; ++i) x[i] = (1 - s) * start[i] + s * end[i];
  // A free body turns about one axis between its boundary orientations, R₀ exp(s log(R₀ᵀR₁)),
  // which stays on SO(3) where the straight line would not.
  using Rotation = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
  for (size_t base : rotations_) {
    const Rotation R0 = Eigen::Map<const Rotation>(start.data() + base),
                   R1 = Eigen::Map<const Rotation>(end.data() + base);
    if (!R0.isUnitary(1e-6) || !R1.isUnitary(1e-6)) continue;
    Eigen::AngleAxisd turn(R0.transpose() * R1);
    turn.angle() *= s;
    Eigen::Map<Rotation>(x.data() + base) = R0 * turn.toRotationMatrix();
  }
  if (!spec_.guess_paths.empty()) {
    const std::vector<double> zero(std::max(nx_, nu_), 0.0);  // the paths depend on t alone
    paths_.eval(load(t, zero.data(), zero.data()), nullptr, out_);
    const size_t count = paths_.count();
    for (size_t f = 0; f < count; ++f) {
      const size_t c = spec_.guess_paths[f].first.coordinate;
      x[c] = out_[f];
      x[nq_ + c] = 0.0;
    }
    for (size_t e = 0; e < paths_.pattern().size(); ++e) {
      const auto [f, column] = paths_.pattern()[e];
      if (column == 0) x[nq_ + spec_.guess_paths[f].first.coordinate] = out_[count + e];
    }
  }
  if (m_ > 0) dyn_.try_project(t, x.data(), x.data() + nq_, kept_coordinates(keep, nq_));
  return x;
}

std::vector<double> Transcription::make_guess() {
  std::vector<double> x(n_, 0.0), xl(n_), xu(n_), gl(rows_), gu(rows_);
  bounds(xl.data(), xu.data(), gl.data(), gu.data());
  if (free_T_) x[0] = T_;
  const std::vector<double> start = boundary_state(false), end = boundary_state(true);
  auto clamp = [&](size_t i, double v) { return std::min(std::max(v, xl[i]), xu[i]); };
  std::vector<double> u0(nu_), times;
  for (size_t c = 0; c < nu_; ++c)
    u0[c] = clamp(ui(0, 1, c), spec_.controls[c].guess.value_or(0.0));
  for (int k = 0; k < N_; ++k)
    for (int j = 0; j < d_; ++j) times.push_back(T_ * (k + rad_.tau[static_cast<size_t>(j)]) / N_);
  times.push_back(T_);
  const bool simulated =
      spec_.guess == "simulation" ||
      (spec_.guess.empty() && spec_.guess_paths.empty() && spec_.guess_file.empty() && m_ > 0);
  std::vector<std::vector<double>> states;
  std::optional<std::vector<std::vector<double>>> guessed_controls;
  if (!spec_.guess_file.empty()) {
    std::vector<std::string> names;
    for (size_t c : controls_) names.push_back(eq_.model->inputs[c].name);
    FileGuess file = read_file_guess(spec_.guess_file, *cm_, names, times, T_);
    states = std::move(file.states);
    guessed_controls = std::move(file.controls);
    // A file of another model or mesh may be off the constraints: projected as paths are.
    for (size_t p = 0; p < states.size() && m_ > 0; ++p)
      dyn_.try_project(times[p], states[p].data(), states[p].data() + nq_,
                       std::vector<bool>(nq_, false));
  } else if (simulated) {
    // Controls with a guess are held at it; the others fly the model's own schedule.
    std::vector<std::optional<double>> held(nu_);
    for (size_t c = 0; c < nu_; ++c)
      if (spec_.controls[c].guess) held[c] = u0[c];
    SimulatedGuess flown = simulated_states(
        dyn_, controls_, held,
        std::vector<double>(start.begin(), start.begin() + static_cast<long>(nq_)),
        std::vector<double>(start.begin() + static_cast<long>(nq_), start.end()), times);
    states = std::move(flown.states);
    if (!flown.controls.empty()) guessed_controls = std::move(flown.controls);
  }
  // The components a projection keeps: the fixed boundary values at the ends.
  std::vector<bool> keep_start(nx_, false), keep_end(nx_, false), keep_none(nx_, false);
  if (spec_.initial)
    for (const BoundaryValue& b : *spec_.initial)
      keep_start[state_index(b.state, *cm_)] = b.fixed();
  for (const BoundaryValue& b : final_) keep_end[state_index(b.state, *cm_)] = b.fixed();
  for (int k = 0; k < N_; ++k) {
    // From a guess file or a simulation, interval k's control is the one at its first
    // collocation point, a polynomial control's at each point (for a file of the same mesh,
    // exactly its controls there), clipped to the bounds.
    for (size_t c = 0; c < nu_; ++c)
      for (int j = 1; j <= control_points(c); ++j) {
        const size_t i = ui(k, j, c);
        x[i] = guessed_controls ? clamp(i, (*guessed_controls)[static_cast<size_t>(k * d_ + j)][c])
                                : u0[c];
      }
    for (size_t c : constant_)  // one value over the horizon: interval 0's
      if (k > 0) x[ui(k, 1, c)] = x[ui(0, 1, c)];
    for (int j = 0; j <= d_; ++j) {
      const size_t p = static_cast<size_t>(k * d_ + j);
      const bool first = k == 0 && j == 0, last = k == N_ - 1 && j == d_;
      const std::vector<double> guessed = states.empty() ? guessed_state(times[p], start, end,
                                                                         first  ? keep_start
                                                                         : last ? keep_end
                                                                                : keep_none)
                                                         : states[p];
      for (size_t i = 0; i < nx_; ++i)
        // A simulated or projected state stays as it is (on the constraints; Ipopt moves it
        // into the bounds itself), an interpolated one is clipped to them.
        x[xi(k, j) + i] = states.empty() && m_ == 0 ? clamp(xi(k, j) + i, guessed[i]) : guessed[i];
    }
  }
  // Multipliers from the forward dynamics at the guessed states (0 where it cannot solve).
  std::vector<double> qdot(nq_), a(nv_), lambda(m_);
  for (int k = 0; k < N_ && m_ > 0; ++k)
    for (int j = 1; j <= d_; ++j) {
      const double* u = control(x.data(), k, j);
      for (size_t c = 0; c < nu_; ++c) dyn_.hold_input(controls_[c], u[c]);
      const double* s = x.data() + xi(k, j);
      try {
        dyn_.forward(time(x.data(), k, j), s, s + nq_, qdot.data(), a.data(), lambda.data());
        std::copy(lambda.begin(), lambda.end(), x.begin() + static_cast<long>(li(k, j)));
      } catch (const SimulationError&) {
      }
    }
  return x;
}

const std::vector<double>& Transcription::load(double t, const double* x, const double* u) {
  const CompiledModel& c = *cm_;
  in_[0] = t;
  std::copy(x, x + nx_, in_.begin() + static_cast<long>(c.q_offset()));
  const std::vector<double>& p = dyn_.parameters();
  std::copy(p.begin(), p.end(), in_.begin() + static_cast<long>(c.p_offset()));
  if (c.k > 0) {  // the other inputs follow their expressions u(t), u̇, ü
    sig_.resize(c.inputs.num_outputs());
    sig_work_.resize(std::max<size_t>(c.inputs.work_size(), 1));
    c.inputs.eval(in_.data(), sig_.data(), sig_work_.data());
    std::copy(sig_.begin(), sig_.end(), in_.begin() + static_cast<long>(c.u_offset()));
  }
  for (size_t i = 0; i < nu_; ++i) {
    in_[c.u_offset() + controls_[i]] = u[i];
    in_[c.u_offset() + c.k + controls_[i]] = 0.0;
    in_[c.u_offset() + 2 * c.k + controls_[i]] = 0.0;
  }
  return in_;
}

// docs/theory.md §10: x'(t_kj) = (1/h) Σ_l D_jl X_{k,l}, h = T/N; residual of the index-1 DAE
// r = (q' − K(q) v, M v' + Gᵀλ − (h + Q), G v' + c + 2αĊ + α²C) (§4.3).
void Transcription::collocation_derivative(const double* x, int k, int j) {
  const double h = horizon(x) / N_;
  std::fill(xp_.begin(), xp_.end(), 0.0);
  for (int l = 0; l <= d_; ++l) {
    const double f = rad_.derivative(j, l) / h;
    const double* X = state(x, k, l);
    for (size_t i = 0; i < nx_; ++i) xp_[i] += f * X[i];
  }
}

// docs/theory.md §10: ρ(q, v, u, a, λ) and its derivatives in one tape evaluation, a = v'.
void Transcription::eval_residual(const double* x, int k, int j) {
  collocation_derivative(x, k, j);
  const double* X = state(x, k, j);
  rin_ = load(time(x, k, j), X, control(x, k, j));
  rin_.insert(rin_.end(), xp_.begin() + static_cast<long>(nq_), xp_.end());
  rin_.insert(rin_.end(), multipliers(x, k, j), multipliers(x, k, j) + m_);
  rin_.push_back(dyn_.baumgarte());
  rout_.resize(dae_->num_outputs());
  dae_->eval(rin_.data(), rout_.data());
  const size_t nr = dae_->rows();
  if (analysis_detail::all_finite(rout_.data() + nr, rout_.data() + rout_.size())) return;
  const std::vector<double> values(rout_.begin(), rout_.begin() + static_cast<long>(nr));
  analysis_detail::eval_off_kink(rin_.data() + cm_->q_offset(), nx_, rout_.data() + nr,
                                 rout_.data() + rout_.size(),
                                 [&] { dae_->eval(rin_.data(), rout_.data()); });
  std::copy(values.begin(), values.end(), rout_.begin());
}

void Transcription::evaluate_points(const double* x) {
  if (!x_at_.empty() && std::equal(x, x + n_, x_at_.begin())) return;
  const size_t points = static_cast<size_t>(N_ * d_), nr = dae_->num_outputs(),
               nf = fun_.num_outputs();
  xp_at_.resize(points * nx_);
  rho_at_.resize(points * nr);
  fun_at_.resize(points * nf);
  for (int k = 0; k < N_; ++k)
    for (int j = 1; j <= d_; ++j) {
      const size_t p = static_cast<size_t>(k * d_ + j - 1);
      eval_residual(x, k, j);  // loads the point's tape inputs, which eval_point reads too
      std::copy(xp_.begin(), xp_.end(), xp_at_.begin() + static_cast<long>(p * nx_));
      std::copy(rout_.begin(), rout_.end(), rho_at_.begin() + static_cast<long>(p * nr));
      eval_point(x, k, j);
      std::copy(out_.begin(), out_.end(), fun_at_.begin() + static_cast<long>(p * nf));
    }
  x_at_.assign(x, x + n_);
}

void Transcription::residual_terms(const double* x, int k, int j, size_t col,
                                   std::vector<Term>& t) const {
  t.clear();
  for_each_residual_term(x, xp_.data(), k, j, col, [&](size_t v, double c) {
    t.push_back({v, c});
  });
}

// docs/theory.md §10, "Homotopy": the tracking term.
double Transcription::tracking(const double* x) const {
  double J = 0.0;
  if (track_ > 0)
    for_each_node([&](size_t at) {
      for (size_t i = 0; i < nx_; ++i) {
        const double e = x[at + i] - guess_[at + i];
        J += track_ * track_scale_[i] * e * e;
      }
    });
  return J;
}

double Transcription::objective(const double* x) {
  evaluate_points(x);
  const double h = horizon(x) / N_;
  double J = 0.0;
  const size_t points = static_cast<size_t>(N_ * d_);
  for (size_t p = 0; p < points; ++p) {
    // docs/theory.md §10: ∫ L ≈ h Σ b_j L_kj; mean(M) = (1/T) ∫ M ≈ (1/N) Σ b_j M_kj.
    const double* f = point_fun(p);
    J += rad_.b[p % static_cast<size_t>(d_)] * (h * f[kIntegrand] + f[kMean] / N_);
  }
  // The terminal point (T, X_{N,0}) is the last collocation point, with the multipliers there.
  return sign_ * (J + point_fun(points - 1)[kTerminal]) + tracking(x);
}

void Transcription::gradient(const double* x, double* grad) {
  std::fill(grad, grad + n_, 0.0);
  evaluate_points(x);
  const double T = horizon(x), h = T / N_;
  const size_t nf = fun_.count();
  for (int k = 0; k < N_; ++k)
    for (int j = 1; j <= d_; ++j) {
      // The integrand's weight h b_j depends on T, the mean's b_j / N does not.
      const double w = sign_ * h * rad_.b[static_cast<size_t>(j - 1)],
                   wm = sign_ * rad_.b[static_cast<size_t>(j - 1)] / N_;
      const double* out = point_fun(static_cast<size_t>(k * d_ + j - 1));
      if (free_T_) grad[0] += w / T * out[kIntegrand];
      for (size_t e = 0; e < fun_.pattern().size(); ++e) {
        const auto [f, c] = fun_.pattern()[e];
        if (f != kIntegrand && f != kMean) continue;
        const double d = (f == kMean ? wm : w) * out[nf + e];
        if (c != 0)
          grad[point_variable(c, k, j)] += d;
        else if (free_T_)
          grad[0] += d * (k + rad_.tau[static_cast<size_t>(j)]) / N_;
      }
    }
  const double* out = point_fun(static_cast<size_t>(N_ * d_ - 1));  // the terminal point
  for (size_t e = 0; e < fun_.pattern().size(); ++e) {
    const auto [f, c] = fun_.pattern()[e];
    if (f != kTerminal) continue;
    const double d = sign_ * out[nf + e];
    if (c != 0)
      grad[point_variable(c, N_ - 1, d_)] += d;
    else if (free_T_)
      grad[0] += d;
  }
  if (track_ > 0)
    for_each_node([&](size_t at) {
      for (size_t i = 0; i < nx_; ++i)
        grad[at + i] += 2 * track_ * track_scale_[i] * (x[at + i] - guess_[at + i]);
    });
}

void Transcription::constraint_values(const double* x, double* g) {
  // docs/theory.md §10: r = ρ + (q', 0, 0) at each collocation point, then the path constraints.
  evaluate_points(x);
  const size_t nr = nx_ + m_, points = static_cast<size_t>(N_ * d_);
  for (size_t p = 0; p < points; ++p) {
    const double *rho = point_rho(p), *xp = point_xp(p);
    double* r = g + p * nr;
    for (size_t i = 0; i < nq_; ++i) r[i] = xp[i] + rho[i];
    std::copy(rho + nq_, rho + nr, r + nq_);
    if (np_ > 0)
      std::copy(point_fun(p) + kFirstPath, point_fun(p) + kFirstPath + np_,
                g + path_rows_ + p * np_);
  }
  const size_t periodic_at = path_rows_ + static_cast<size_t>(N_ * d_) * np_ + start_rows_.size();
  for (size_t r = 0; r < periodic_.size(); ++r)
    g[periodic_at + r] = state(x, N_, 0)[periodic_[r]] - state(x, 0, 0)[periodic_[r]];
  // A constant control: U_{k+1,c} − U_{k,c} = 0 (docs/theory.md §10, "Constant controls").
  const size_t constant_at = periodic_at + periodic_.size();
  for (size_t r = 0; r < constant_.size(); ++r)
    for (int k = 0; k + 1 < N_; ++k)
      g[constant_at + r * static_cast<size_t>(N_ - 1) + static_cast<size_t>(k)] =
          x[ui(k + 1, 1, constant_[r])] - x[ui(k, 1, constant_[r])];
  const size_t turning_at = rows_ - turning_.size();
  for (size_t r = 0; r < turning_.size(); ++r) {
    const auto [base, w] = turning_[r];
    g[turning_at + r] = turning(state(x, 0, 0), state(x, N_, 0), base, w);
  }
  if (start_rows_.empty()) return;
  const size_t at = path_rows_ + static_cast<size_t>(N_ * d_) * np_;
  const double* u = control(x, 0, 0);
  for (size_t c = 0; c < nu_; ++c) dyn_.hold_input(controls_[c], u[c]);
  std::vector<double> C(2 * m_);
  if (m_ > 0) dyn_.constraints(0.0, state(x, 0, 0), state(x, 0, 0) + nq_, C.data(), C.data() + m_);
  for (size_t r = 0; r < start_rows_.size(); ++r) {
    const size_t i = start_rows_[r];
    g[at + r] = i < 2 * m_ ? C[i] : orthonormality(state(x, 0, 0), i - 2 * m_);
  }
}

// docs/theory.md §10, "Free bodies": component w of vee(skew(AᵀB)), A = R(0), B = R(T):
// ((AᵀB)_ij − (AᵀB)_ji)/2 with (AᵀB)_ij = Σ_a A_ai B_aj.
double Transcription::turning(const double* X0, const double* XT, size_t base, size_t w) const {
  const double *A = X0 + base, *B = XT + base;
  const auto [i, j] = kSkewPairs[w];
  double s = 0.0;
  for (size_t a = 0; a < 3; ++a)
    s += (A[3 * a + i] * B[3 * a + j] - A[3 * a + j] * B[3 * a + i]) / 2;
  return s;
}

template <class EmitA, class EmitB>
void Transcription::turning_gradient(const double* X0, const double* XT, size_t base, size_t w,
                                     EmitA&& on_start, EmitB&& on_end) const {
  const double *A = X0 + base, *B = XT + base;
  const auto [i, j] = kSkewPairs[w];
  for (size_t a = 0; a < 3; ++a) {
    on_start(base + 3 * a + i, B[3 * a + j] / 2);
    on_start(base + 3 * a + j, -B[3 * a + i] / 2);
    on_end(base + 3 * a + j, A[3 * a + i] / 2);
    on_end(base + 3 * a + i, -A[3 * a + j] / 2);
  }
}

// docs/theory.md §10, "Free bodies": (RᵀR − 1)_ij = Σ_a R_ai R_aj − δ_ij, entry `which` of the
// kOrthonormalPairs of each body in turn.
double Transcription::orthonormality(const double* X, size_t which) const {
  const double* R = X + rotations_[which / 6];
  const auto [i, j] = kOrthonormalPairs[which % 6];
  double sum = i == j ? -1.0 : 0.0;
  for (size_t a = 0; a < 3; ++a) sum += R[3 * a + i] * R[3 * a + j];
  return sum;
}

void Transcription::jacobian(const double* x, double* values) {
  std::fill(values, values + nz_.size(), 0.0);
  size_t e = 0;
  walk_jacobian(x, [&](size_t, size_t, double v) { values[slot_[e++]] += v; });
}

template <class Emit>
void Transcription::walk_jacobian(const double* x, Emit&& emit) {
  const double T = horizon(x), h = T / N_;
  const size_t nr = nx_ + m_;
  const size_t nf = fun_.count();
  evaluate_points(x);
  for (int k = 0; k < N_; ++k)
    for (int j = 1; j <= d_; ++j) {
      const size_t p = static_cast<size_t>(k * d_ + j - 1), row = p * nr;
      const double *rho = point_rho(p), *xp = point_xp(p);
      // r_q = q' − q̇(q, v): ∂/∂q' through the collocation derivative, the rest from ρ.
      for (int l = 0; l <= d_; ++l) {
        const double f = rad_.derivative(j, l) / h;
        for (size_t i = 0; i < nq_; ++i) emit(row + i, xi(k, l) + i, f);
      }
      if (free_T_)  // ∂x'/∂T = −x'/T
        for (size_t i = 0; i < nq_; ++i) emit(row + i, 0, -xp[i] / T);
      for (size_t e = 0; e < dae_->pattern().size(); ++e) {
        // (a lambda may not capture a structured binding before C++20: clang 14 refuses it)
        const size_t at = row + dae_->pattern()[e].first, col = dae_->pattern()[e].second;
        const double d = rho[nr + e];
        for_each_residual_term(x, xp, k, j, col, [&](size_t v, double c) { emit(at, v, d * c); });
      }
      if (np_ == 0) continue;
      // Path constraints at (t_kj, X_{k,j}, U_k).
      const size_t prow = path_rows_ + p * np_;
      const double* out = point_fun(p);
      for (size_t e = 0; e < fun_.pattern().size(); ++e) {
        const auto [f, c] = fun_.pattern()[e];
        if (f < kFirstPath) continue;
        const double v = out[nf + e];
        if (c != 0)
          emit(prow + f - kFirstPath, point_variable(c, k, j), v);
        else if (free_T_)
          emit(prow + f - kFirstPath, 0, v * (k + rad_.tau[static_cast<size_t>(j)]) / N_);
      }
    }
  // x(T) − x(0) of the periodic components.
  const size_t periodic_at = path_rows_ + static_cast<size_t>(N_ * d_) * np_ + start_rows_.size();
  for (size_t r = 0; r < periodic_.size(); ++r) {
    emit(periodic_at + r, xi(N_, 0) + periodic_[r], 1.0);
    emit(periodic_at + r, xi(0, 0) + periodic_[r], -1.0);
  }
  const size_t constant_at = periodic_at + periodic_.size();
  for (size_t r = 0; r < constant_.size(); ++r)
    for (int k = 0; k + 1 < N_; ++k) {
      const size_t row = constant_at + r * static_cast<size_t>(N_ - 1) + static_cast<size_t>(k);
      emit(row, ui(k + 1, 1, constant_[r]), 1.0);
      emit(row, ui(k, 1, constant_[r]), -1.0);
    }
  const size_t turning_at = rows_ - turning_.size();
  for (size_t r = 0; r < turning_.size(); ++r) {
    const auto [base, w] = turning_[r];
    turning_gradient(
        state(x, 0, 0), state(x, N_, 0), base, w,
        [&](size_t c, double v) { emit(turning_at + r, xi(0, 0) + c, v); },
        [&](size_t c, double v) { emit(turning_at + r, xi(N_, 0) + c, v); });
  }
  // The invariants imposed at t = 0.
  if (start_rows_.empty()) return;
  std::vector<size_t> row_of(invariants(), rows_);
  for (size_t r = 0; r < start_rows_.size(); ++r)
    row_of[start_rows_[r]] = path_rows_ + static_cast<size_t>(N_ * d_) * np_ + r;
  const double* u = control(x, 0, 0);
  for (size_t c = 0; c < nu_; ++c) dyn_.hold_input(controls_[c], u[c]);
  invariant_gradients(0.0, state(x, 0, 0), [&](size_t i, size_t col, double v) {
    if (row_of[i] < rows_) emit(row_of[i], xi(0, 0) + col, v);
  });
}

// ∂C/∂q, ∂Ċ/∂q and ∂Ċ/∂v = G from their own tape (at the inputs dyn.constraints loads); no KKT
// solve, so no singular-matrix stop. Constraints without explicit t: no ∂/∂T term.
template <class Emit>
void Transcription::invariant_gradients(double t, const double* X, Emit&& emit) {
  // ∂(RᵀR − 1)_ij/∂R_ab = δ_bi R_aj + δ_bj R_ai (docs/theory.md §10, "Free bodies").
  for (size_t w = 0; w < 6 * rotations_.size(); ++w) {
    const size_t base = rotations_[w / 6];
    const auto [i, j] = kOrthonormalPairs[w % 6];
    for (size_t a = 0; a < 3; ++a) {
      emit(2 * m_ + w, base + 3 * a + i, X[base + 3 * a + j]);
      emit(2 * m_ + w, base + 3 * a + j, X[base + 3 * a + i]);
    }
  }
  if (m_ == 0) return;
  std::vector<double> C(m_), Cdot(m_);
  dyn_.constraints(t, X, X + nq_, C.data(), Cdot.data());  // loads the tape inputs at (t, X)
  invariant_jac_.eval(dyn_.last_inputs().data(), out_);
  for (size_t e = 0; e < invariant_jac_.pattern().size(); ++e) {
    const auto [i, col] = invariant_jac_.pattern()[e];
    emit(i, col, out_[e]);
  }
}

std::vector<Transcription::ImpliedGap> Transcription::implied_final_gaps(const double* x) {
  std::vector<ImpliedGap> gaps;
  if (implied_.empty()) return gaps;
  const CompiledModel& c = *cm_;
  std::vector<double> end(state(x, N_, 0), state(x, N_, 0) + nx_);
  std::vector<bool> keep(nx_, false);
  for (const BoundaryValue& b : final_) keep[state_index(b.state, *cm_)] = b.fixed();
  const double* u = control(x, N_ - 1, d_);
  for (size_t c = 0; c < nu_; ++c) dyn_.hold_input(controls_[c], u[c]);
  dyn_.try_project(horizon(x), end.data(), end.data() + nq_, kept_coordinates(keep, nq_));
  for (const BoundaryValue& b : implied_) {
    const size_t i = state_index(b.state, *cm_);
    const std::string name = i < nq_ ? c.coordinate_names[i] : c.velocity_names[i - nq_];
    gaps.push_back({fmt::format("final value of '{}' (implied by the constraints)", name),
                    b.bounds.lower, std::fabs(state(x, N_, 0)[i] - b.bounds.lower),
                    std::fabs(end[i] - b.bounds.lower)});
  }
  return gaps;
}

// docs/theory.md §10, "Scaling": a variable's nominal magnitude is the largest it takes in the
// starting point (over every collocation point for a state component, a multiplier or a
// control) or as a finite bound, never below 1; Ipopt works in x̃ = x / nominal. A constraint is
// scaled so that its largest gradient entry in x̃ at the starting point is at most 100 (Ipopt's
// own rule, nlp_scaling_max_gradient, applied after the variables are scaled).
void Transcription::scaling(double* x_scale, double* g_scale, double& f_scale) {
  std::vector<double> xl(n_), xu(n_), gl(rows_), gu(rows_);
  bounds(xl.data(), xu.data(), gl.data(), gu.data());
  const auto magnitude = [&](size_t v) {
    double a = std::fabs(guess_[v]);
    for (double b : {xl[v], xu[v]})
      if (std::fabs(b) < 1e19) a = std::max(a, std::fabs(b));
    return a;
  };
  std::vector<double> nominal(n_, 1.0);
  // Variables of one kind share a magnitude: a state component over all its points, a
  // multiplier over all points, a control over all intervals.
  const auto share = [&](size_t width, auto&& offsets) {
    std::vector<double> big(width, 1.0);
    offsets([&](size_t at) {
      for (size_t i = 0; i < width; ++i) big[i] = std::max(big[i], magnitude(at + i));
    });
    offsets([&](size_t at) { std::copy(big.begin(), big.end(), nominal.begin() + at); });
  };
  share(nx_, [&](auto&& f) {
    for (int k = 0; k <= N_; ++k)
      for (int j = 0; j < (k < N_ ? d_ : 1); ++j) f(xi(k, j));
  });
  share(m_, [&](auto&& f) {
    for (int k = 0; k < N_; ++k)
      for (int j = 1; j <= d_; ++j) f(li(k, j));
  });
  for (size_t c = 0; c < nu_; ++c)  // a control over all intervals and points
    share(1, [&](auto&& f) {
      for (int k = 0; k < N_; ++k)
        for (int j = 1; j <= control_points(c); ++j) f(ui(k, j, c));
    });
  if (free_T_) nominal[0] = std::max(1.0, magnitude(0));
  for (size_t v = 0; v < n_; ++v) x_scale[v] = 1.0 / nominal[v];
  std::vector<double> values(nz_.size()), biggest(rows_, 0.0);
  jacobian(guess_.data(), values.data());
  for (size_t e = 0; e < nz_.size(); ++e) {
    const auto [r, c] = nz_[e];
    biggest[r] = std::max(biggest[r], std::fabs(values[e]) * nominal[c]);
  }
  for (size_t r = 0; r < rows_; ++r) g_scale[r] = biggest[r] > 100 ? 100 / biggest[r] : 1.0;
  std::vector<double> grad(n_);
  gradient(guess_.data(), grad.data());
  double gmax = 0.0;
  for (size_t v = 0; v < n_; ++v) gmax = std::max(gmax, std::fabs(grad[v]) * nominal[v]);
  f_scale = gmax > 100 ? 100 / gmax : 1.0;
}

std::string Transcription::describe(size_t row, const double* x) const {
  const CompiledModel& c = *cm_;
  const size_t nr = nx_ + m_;
  if (row < path_rows_) {
    const size_t p = row / nr, i = row % nr;
    const double t = time(x, static_cast<int>(p) / d_, static_cast<int>(p) % d_ + 1);
    if (i < nq_) return fmt::format("kinematics of '{}' at t = {:.6g}", c.coordinate_names[i], t);
    if (i < nx_)
      return fmt::format("equation of motion of '{}' at t = {:.6g}", c.velocity_names[i - nq_], t);
    return fmt::format("constraint '{}' (acceleration level) at t = {:.6g}",
                       c.constraint_names[i - nx_], t);
  }
  row -= path_rows_;
  if (row < static_cast<size_t>(N_ * d_) * np_) {
    const size_t p = row / np_;
    return fmt::format("path constraint '{}' at t = {:.6g}", spec_.path[row % np_].name,
                       time(x, static_cast<int>(p) / d_, static_cast<int>(p) % d_ + 1));
  }
  row -= static_cast<size_t>(N_ * d_) * np_;
  if (row + path_rows_ + static_cast<size_t>(N_ * d_) * np_ >= rows_ - turning_.size()) {
    const auto [base, w] = turning_.at(row + path_rows_ + static_cast<size_t>(N_ * d_) * np_ -
                                       (rows_ - turning_.size()));
    const std::string& r11 = c.coordinate_names[base];
    return fmt::format("periodicity of '{}' (R(T) = R(0) about {})", r11.substr(0, r11.size() - 4),
                       "xyz"[w]);
  }
  if (row >= start_rows_.size() + periodic_.size()) {
    const size_t r = row - start_rows_.size() - periodic_.size(), n = static_cast<size_t>(N_ - 1);
    return fmt::format("constant control '{}' between intervals {} and {}",
                       eq_.model->inputs[controls_[constant_.at(r / n)]].name, r % n, r % n + 1);
  }
  if (row >= start_rows_.size()) {
    const size_t i = periodic_.at(row - start_rows_.size());
    return fmt::format("periodicity of '{}'",
                       i < nq_ ? c.coordinate_names[i] : c.velocity_names[i - nq_]);
  }
  const size_t i = start_rows_.at(row);
  if (i >= 2 * m_) {
    const std::string& r11 = c.coordinate_names[rotations_[(i - 2 * m_) / 6]];
    const auto [a, b] = kOrthonormalPairs[(i - 2 * m_) % 6];
    return fmt::format("orthonormality of '{}' (RᵀR = 1, entry {}{}) at t = 0",
                       r11.substr(0, r11.size() - 4), a + 1, b + 1);
  }
  return fmt::format("constraint '{}' {}at t = 0", c.constraint_names[i % m_],
                     i < m_ ? "" : "rate ");
}

}  // namespace lagrange::collocation
