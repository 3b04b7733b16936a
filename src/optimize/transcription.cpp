#include "optimize/transcription.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "optimize/simulated_guess.hpp"

namespace lagrange::collocation {

namespace {

std::vector<std::string> control_names(const Model& model, const OptimalControlSpec& spec) {
  std::vector<std::string> names;
  for (const ControlSpec& c : spec.controls) names.push_back(model.inputs.at(c.input).name);
  return names;
}

std::vector<GiNaC::ex> point_functions(const OptimalControlSpec& spec) {
  std::vector<GiNaC::ex> fs{spec.integrand, spec.terminal};
  for (const PathConstraintSpec& p : spec.path) fs.push_back(p.expr);
  return fs;
}

/// Index in x = (q, v) of a state reference (plain coordinates: q index = v index).
size_t state_index(const StateRef& s, size_t nq) {
  return s.velocity ? nq + s.coordinate : s.coordinate;
}

}  // namespace

Transcription::Transcription(const Equations& eq, std::shared_ptr<const CompiledModel> cm,
                             Dynamics& dyn, const OptimalControlSpec& spec, int intervals,
                             int degree, const std::vector<double>& q0,
                             const std::vector<double>& v0)
    : eq_(eq),
      cm_(cm),
      dyn_(dyn),
      spec_(spec),
      jac_(eq, cm, control_names(*eq.model, spec)),
      fun_(eq, *cm, point_functions(spec),
           [&] {
             std::vector<size_t> c;
             for (const ControlSpec& s : spec.controls) c.push_back(s.input);
             return c;
           }()),
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
      q0_(q0),
      v0_(v0) {
  if (intervals < 1) throw std::invalid_argument("expected at least 1 collocation interval");
  for (const ControlSpec& c : spec.controls) controls_.push_back(c.input);
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
  size_t fixed = 0;
  if (spec.initial)
    for (const BoundaryValue& b : *spec.initial) fixed += b.fixed();
  consistency_ = m_ > 0 && spec.initial.has_value() && fixed < nx_;

  block_ = static_cast<size_t>(d_) * (nx_ + m_) + nu_;
  first_ = free_T_ ? 1 : 0;
  n_ = first_ + static_cast<size_t>(N_) * block_ + nx_;
  path_rows_ = static_cast<size_t>(N_ * d_) * (nx_ + m_);
  rows_ = path_rows_ + static_cast<size_t>(N_ * d_) * np_ + (consistency_ ? 2 * m_ : 0) +
          (final_invariants_ ? 2 * m_ : 0);
  in_.assign(cm->input_count(), 0.0);
  xp_.assign(nx_, 0.0);
  // The Jacobian's pattern: one walk at the starting point, entries merged by position.
  guess_ = make_guess();
  const std::vector<double>& x0 = guess_;
  std::map<std::pair<size_t, size_t>, size_t> where;
  walk_jacobian(x0.data(), [&](size_t r, size_t c, double) {
    auto [it, added] = where.emplace(std::make_pair(r, c), nz_.size());
    if (added) nz_.emplace_back(r, c);
    slot_.push_back(it->second);
  });
}

size_t Transcription::xi(int k, int j) const {
  if (j == d_) return xi(k + 1, 0);
  return first_ + static_cast<size_t>(k) * block_ + static_cast<size_t>(j) * nx_;
}
size_t Transcription::li(int k, int j) const {
  return first_ + static_cast<size_t>(k) * block_ + static_cast<size_t>(d_) * nx_ +
         static_cast<size_t>(j - 1) * m_;
}
size_t Transcription::ui(int k) const {
  return first_ + static_cast<size_t>(k) * block_ + static_cast<size_t>(d_) * (nx_ + m_);
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
  for (int k = 0; k <= N_; ++k)
    for (int j = 0; j < (k < N_ ? d_ : 1); ++j)
      for (const StateBound& b : spec_.bounds) {
        const size_t i = xi(k, j) + state_index(b.state, nq_);
        xl[i] = finite(b.bounds.lower);
        xu[i] = finite(b.bounds.upper);
      }
  for (int k = 0; k < N_; ++k)
    for (size_t c = 0; c < nu_; ++c) {
      xl[ui(k) + c] = finite(spec_.controls[c].bounds.lower);
      xu[ui(k) + c] = finite(spec_.controls[c].bounds.upper);
    }
  auto fix = [&](size_t at, const BoundaryValue& b) {
    xl[at + state_index(b.state, nq_)] = finite(b.bounds.lower);
    xu[at + state_index(b.state, nq_)] = finite(b.bounds.upper);
  };
  if (spec_.initial) {
    for (const BoundaryValue& b : *spec_.initial) fix(xi(0, 0), b);
  } else {
    for (size_t i = 0; i < nx_; ++i)
      xl[i + first_] = xu[i + first_] = i < nq_ ? q0_[i] : v0_[i - nq_];
  }
  for (const BoundaryValue& b : spec_.final) fix(xi(N_, 0), b);
  std::fill(gl, gl + rows_, 0.0);
  std::fill(gu, gu + rows_, 0.0);
  for (size_t p = 0; p < static_cast<size_t>(N_ * d_); ++p)
    for (size_t i = 0; i < np_; ++i) {
      gl[path_rows_ + p * np_ + i] = finite(spec_.path[i].bounds.lower);
      gu[path_rows_ + p * np_ + i] = finite(spec_.path[i].bounds.upper);
    }
}

std::vector<double> Transcription::make_guess() {
  std::vector<double> x(n_, 0.0), xl(n_), xu(n_), gl(rows_), gu(rows_);
  bounds(xl.data(), xu.data(), gl.data(), gu.data());
  if (free_T_) x[0] = T_;
  std::vector<double> start(nx_), end(nx_);
  for (size_t i = 0; i < nx_; ++i) start[i] = i < nq_ ? q0_[i] : v0_[i - nq_];
  if (spec_.initial)
    for (const BoundaryValue& b : *spec_.initial)
      if (b.fixed()) start[state_index(b.state, nq_)] = b.bounds.lower;
  end = start;  // free components keep their start value (clipped to the bounds below)
  for (const BoundaryValue& b : spec_.final)
    if (b.fixed()) end[state_index(b.state, nq_)] = b.bounds.lower;
  auto clamp = [&](size_t i, double v) { return std::min(std::max(v, xl[i]), xu[i]); };
  std::vector<double> u0(nu_), times;
  for (size_t c = 0; c < nu_; ++c) u0[c] = clamp(ui(0) + c, spec_.controls[c].guess.value_or(0.0));
  for (int k = 0; k < N_; ++k)
    for (int j = 0; j < d_; ++j) times.push_back(T_ * (k + rad_.tau[static_cast<size_t>(j)]) / N_);
  times.push_back(T_);
  const bool simulated = spec_.guess == "simulation" || (spec_.guess.empty() && m_ > 0);
  std::vector<std::vector<double>> states;
  if (simulated)
    states = simulated_states(
        dyn_, controls_, u0,
        std::vector<double>(start.begin(), start.begin() + static_cast<long>(nq_)),
        std::vector<double>(start.begin() + static_cast<long>(nq_), start.end()), times);
  for (int k = 0; k < N_; ++k) {
    std::copy(u0.begin(), u0.end(), x.begin() + static_cast<long>(ui(k)));
    for (int j = 0; j <= d_; ++j) {
      const double s = (k + rad_.tau[static_cast<size_t>(j)]) / N_;
      const size_t p = static_cast<size_t>(k * d_ + j);
      for (size_t i = 0; i < nx_; ++i)
        // A simulated state stays as simulated (on the constraints; Ipopt moves it into the
        // bounds itself), an interpolated one is clipped to them.
        x[xi(k, j) + i] =
            states.empty() ? clamp(xi(k, j) + i, (1 - s) * start[i] + s * end[i]) : states[p][i];
    }
  }
  // Multipliers from the forward dynamics at the guessed states (0 where it cannot solve).
  std::vector<double> qdot(nq_), a(nv_), lambda(m_);
  for (int k = 0; k < N_ && m_ > 0; ++k)
    for (int j = 1; j <= d_; ++j) {
      for (size_t c = 0; c < nu_; ++c) dyn_.hold_input(controls_[c], x[ui(k) + c]);
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
    std::vector<double> sig(c.inputs.num_outputs()),
        work(std::max<size_t>(c.inputs.work_size(), 1));
    c.inputs.eval(in_.data(), sig.data(), work.data());
    std::copy(sig.begin(), sig.end(), in_.begin() + static_cast<long>(c.u_offset()));
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
void Transcription::residual(const double* x, int k, int j, double* r) {
  const double h = horizon(x) / N_;
  std::fill(xp_.begin(), xp_.end(), 0.0);
  for (int l = 0; l <= d_; ++l) {
    const double f = rad_.derivative(j, l) / h;
    const double* X = state(x, k, l);
    for (size_t i = 0; i < nx_; ++i) xp_[i] += f * X[i];
  }
  const double* u = control(x, k);
  for (size_t c = 0; c < nu_; ++c) dyn_.hold_input(controls_[c], u[c]);
  const double* X = state(x, k, j);
  dyn_.dae_residual(time(x, k, j), X, X + nq_, xp_.data(), xp_.data() + nq_, multipliers(x, k, j),
                    r);
}

double Transcription::objective(const double* x) {
  const double h = horizon(x) / N_;
  double J = 0.0;
  for (int k = 0; k < N_; ++k)
    for (int j = 1; j <= d_; ++j) {
      fun_.eval(load(time(x, k, j), state(x, k, j), control(x, k)), out_);
      J += h * rad_.b[static_cast<size_t>(j - 1)] * out_[0];
    }
  fun_.eval(load(horizon(x), state(x, N_, 0), control(x, N_ - 1)), out_);
  return sign_ * (J + out_[1]);
}

void Transcription::gradient(const double* x, double* grad) {
  std::fill(grad, grad + n_, 0.0);
  const double T = horizon(x), h = T / N_;
  const size_t cu = 1 + nx_;  // first control column
  const size_t nf = fun_.count();
  for (int k = 0; k < N_; ++k)
    for (int j = 1; j <= d_; ++j) {
      const double w = sign_ * h * rad_.b[static_cast<size_t>(j - 1)];
      fun_.eval(load(time(x, k, j), state(x, k, j), control(x, k)), out_);
      if (free_T_) grad[0] += w / T * out_[0];
      for (size_t e = 0; e < fun_.pattern().size(); ++e) {
        const auto [f, c] = fun_.pattern()[e];
        if (f != 0) continue;
        const double d = w * out_[nf + e];
        if (c == 0) {
          if (free_T_) grad[0] += d * (k + rad_.tau[static_cast<size_t>(j)]) / N_;
        } else if (c < cu) {
          grad[xi(k, j) + c - 1] += d;
        } else {
          grad[ui(k) + c - cu] += d;
        }
      }
    }
  fun_.eval(load(T, state(x, N_, 0), control(x, N_ - 1)), out_);
  for (size_t e = 0; e < fun_.pattern().size(); ++e) {
    const auto [f, c] = fun_.pattern()[e];
    if (f != 1) continue;
    const double d = sign_ * out_[nf + e];
    if (c == 0) {
      if (free_T_) grad[0] += d;
    } else if (c < cu) {
      grad[xi(N_, 0) + c - 1] += d;
    } else {
      grad[ui(N_ - 1) + c - cu] += d;
    }
  }
}

void Transcription::constraint_values(const double* x, double* g) {
  const size_t nr = nx_ + m_;
  for (int k = 0; k < N_; ++k)
    for (int j = 1; j <= d_; ++j) {
      const size_t p = static_cast<size_t>(k * d_ + j - 1);
      residual(x, k, j, g + p * nr);
      if (np_ == 0) continue;
      fun_.eval(load(time(x, k, j), state(x, k, j), control(x, k)), out_);
      std::copy(out_.begin() + 2, out_.begin() + 2 + static_cast<long>(np_),
                g + path_rows_ + p * np_);
    }
  size_t at = path_rows_ + static_cast<size_t>(N_ * d_) * np_;
  for (int end = 0; end < 2; ++end) {
    if (!(end == 0 ? consistency_ : final_invariants_)) continue;
    const int k = end == 0 ? 0 : N_ - 1;
    for (size_t c = 0; c < nu_; ++c) dyn_.hold_input(controls_[c], control(x, k)[c]);
    const double* X = state(x, end == 0 ? 0 : N_, 0);
    dyn_.constraints(end == 0 ? 0.0 : horizon(x), X, X + nq_, g + at, g + at + m_);
    at += 2 * m_;
  }
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
  std::vector<double> r(nr);
  const size_t nf = fun_.count(), cu = 1 + nx_;
  for (int k = 0; k < N_; ++k)
    for (int j = 1; j <= d_; ++j) {
      const size_t row = static_cast<size_t>(k * d_ + j - 1) * nr;
      residual(x, k, j, r.data());  // x'/h in xp_, the controls held
      const double* X = state(x, k, j);
      const ImplicitJacobian J =
          jac_.implicit(dyn_, time(x, k, j), X, X + nq_, xp_.data() + nq_, multipliers(x, k, j));
      // r_q = q' − q̇(q, v): ∂/∂q' through the collocation derivative, −∂q̇/∂(q, v) at X_{k,j}.
      for (int l = 0; l <= d_; ++l) {
        const double f = rad_.derivative(j, l) / h;
        for (size_t i = 0; i < nq_; ++i) emit(row + i, xi(k, l) + i, f);
      }
      for (int o = 0; o < J.qdot_x.outerSize(); ++o)
        for (Eigen::SparseMatrix<double>::InnerIterator it(J.qdot_x, o); it; ++it)
          emit(row + static_cast<size_t>(it.row()), xi(k, j) + static_cast<size_t>(it.col()),
               -it.value());
      if (free_T_)  // ∂x'/∂T = −x'/T
        for (size_t i = 0; i < nq_; ++i) emit(row + i, 0, -xp_[i] / T);
      // (r_v, r_λ) = Φ(q, v, v', λ, u): K = ∂Φ/∂(v', λ), Phi_x = ∂Φ/∂(q, v, u).
      for (int o = 0; o < J.K.outerSize(); ++o)
        for (Eigen::SparseMatrix<double>::InnerIterator it(J.K, o); it; ++it) {
          const size_t rr = row + nq_ + static_cast<size_t>(it.row());
          const size_t c = static_cast<size_t>(it.col());
          if (c < nv_) {
            for (int l = 0; l <= d_; ++l)
              emit(rr, xi(k, l) + nq_ + c, it.value() * rad_.derivative(j, l) / h);
            if (free_T_) emit(rr, 0, -it.value() * xp_[nq_ + c] / T);
          } else {
            emit(rr, li(k, j) + c - nv_, it.value());
          }
        }
      for (int o = 0; o < J.Phi_x.outerSize(); ++o)
        for (Eigen::SparseMatrix<double>::InnerIterator it(J.Phi_x, o); it; ++it) {
          const size_t c = static_cast<size_t>(it.col());
          emit(row + nq_ + static_cast<size_t>(it.row()), c < nx_ ? xi(k, j) + c : ui(k) + c - nx_,
               it.value());
        }
      if (np_ == 0) continue;
      // Path constraints at (t_kj, X_{k,j}, U_k).
      const size_t prow = path_rows_ + static_cast<size_t>(k * d_ + j - 1) * np_;
      fun_.eval(load(time(x, k, j), X, control(x, k)), out_);
      for (size_t e = 0; e < fun_.pattern().size(); ++e) {
        const auto [f, c] = fun_.pattern()[e];
        if (f < 2) continue;
        const double v = out_[nf + e];
        if (c == 0) {
          if (free_T_) emit(prow + f - 2, 0, v * (k + rad_.tau[static_cast<size_t>(j)]) / N_);
        } else {
          emit(prow + f - 2, c < cu ? xi(k, j) + c - 1 : ui(k) + c - cu, v);
        }
      }
    }
  // C = 0, Ċ = 0 at t = 0 and t = T (constraints without explicit t: no ∂/∂T term).
  size_t at = path_rows_ + static_cast<size_t>(N_ * d_) * np_;
  for (int end = 0; end < 2; ++end) {
    if (!(end == 0 ? consistency_ : final_invariants_)) continue;
    const int k = end == 0 ? 0 : N_ - 1;
    const size_t base = xi(end == 0 ? 0 : N_, 0);
    for (size_t c = 0; c < nu_; ++c) dyn_.hold_input(controls_[c], control(x, k)[c]);
    const double* X = x + base;
    // G = ∂Ċ/∂v is a value, ∂C/∂q and ∂Ċ/∂q are derivatives on the Jacobian tape (at the inputs
    // dyn.constraints loads); no KKT solve, so no singular-matrix stop.
    std::vector<double> C(m_), Cdot(m_);
    dyn_.constraints(end == 0 ? 0.0 : T, X, X + nq_, C.data(), Cdot.data());
    const Tape& tape = jac_.tape();
    out_.resize(tape.num_outputs());
    std::vector<double> work(std::max<size_t>(tape.work_size(), 1));
    tape.eval(dyn_.last_inputs().data(), out_.data(), work.data());
    const CompiledModel& cm = *cm_;
    for (size_t e = 0; e < cm.G_pattern.size(); ++e)
      emit(at + m_ + cm.G_pattern[e].first, base + nq_ + cm.G_pattern[e].second,
           out_[cm.G_out() + e]);
    for (size_t e = 0; e < jac_.pattern().size(); ++e) {
      const auto [r, col] = jac_.pattern()[e];
      if (r >= cm.Cdot_out() && r < cm.Cq_out() && col < nq_)  // ∂Ċ/∂q, then ∂C/∂q
        emit(at + (r < cm.C_out() ? m_ + r - cm.Cdot_out() : r - cm.C_out()), base + col,
             out_[jac_.value_count() + e]);
    }
    at += 2 * m_;
  }
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
  const bool final = !consistency_ || row >= 2 * m_;
  return fmt::format("constraint '{}' {}at t = {}", c.constraint_names[row % m_],
                     row % (2 * m_) < m_ ? "" : "rate ",
                     final ? fmt::format("{:.6g}", horizon(x)) : "0");
}

}  // namespace lagrange::collocation
