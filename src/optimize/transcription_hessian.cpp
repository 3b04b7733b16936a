// The exact Hessian of the NLP's Lagrangian σ∇²J + Σ y_r ∇²g_r (docs/theory.md §10, "Hessian"):
// at each collocation point the second derivatives of Σ μ·r(q, v, u, a, λ) for the DAE residual
// r, with a = v' linear in the states (the collocation derivative), of the weighted objective
// and path-constraint functions, and at t = 0 of the weighted invariants; compiled symbolically
// like the first derivatives and scattered through the linear maps onto the NLP's variables.

#include <fmt/format.h>

#include <map>

#include "analysis/off_kink.hpp"
#include "optimize/transcription.hpp"

namespace lagrange::collocation {

namespace {

/// H·∂z_a·∂z_b scattered onto the lower triangle: a local diagonal entry (a = b) gives each
/// variable pair once; an off-diagonal one (a > b) stands for both (a, b) and (b, a), so it
/// counts twice where its two variables coincide.
template <class Emit>
void scatter(bool diagonal, const std::vector<Term>& A, const std::vector<Term>& B, double H,
             Emit& emit) {
  for (const Term& a : A)
    for (const Term& b : diagonal ? A : B) {
      if (diagonal && a.variable < b.variable) continue;
      const double v = H * a.coefficient * b.coefficient;
      const double twice = !diagonal && a.variable == b.variable ? 2.0 : 1.0;
      emit(std::max(a.variable, b.variable), std::min(a.variable, b.variable), twice * v);
    }
}

/// Distinct nodes of an expression DAG (GiNaC shares subexpressions: a tree walk could take
/// exponentially long), counted up to `limit`.
size_t distinct_terms(const GiNaC::ex& e, size_t limit) {
  std::map<GiNaC::ex, bool, GiNaC::ex_is_less> seen;
  std::vector<GiNaC::ex> stack{e};
  while (!stack.empty() && seen.size() <= limit) {
    const GiNaC::ex top = stack.back();
    stack.pop_back();
    if (!seen.emplace(top, true).second) continue;
    for (size_t i = 0; i < top.nops(); ++i) stack.push_back(top.op(i));
  }
  return seen.size();
}

}  // namespace

void Transcription::prepare_hessian(HessianChoice choice,
                                    std::shared_ptr<const SecondDerivatives> dae,
                                    Evaluation evaluation, const MachineCodeOptions& machine_code) {
  const Equations& eq = eq_;
  const CompiledModel& cm = *cm_;
  const std::vector<GiNaC::ex> out = dynamics_expressions(eq, cm);
  const std::vector<GiNaC::symbol> base = eq.tape_inputs();
  std::vector<size_t> state_columns;  // q, v, then the controls
  for (size_t i = 0; i < nx_; ++i) state_columns.push_back(cm.q_offset() + i);
  for (size_t c : controls_) state_columns.push_back(cm.u_offset() + c);

  // Σ μ_r r_r (docs/theory.md §4.3): r_q = q' − q̇ (q' linear: no second derivative),
  // r_v = M a + Gᵀλ − (h + Q), r_λ = G a + c + 2αĊ + α²C; an earlier stage's when given.
  h_dae_ = std::move(dae);
  if (!h_dae_) {
    const ResidualSymbols rs(nv_, m_);
    const std::vector<GiNaC::symbol> mu = numbered_symbols("hess_mu", nx_ + m_);
    const std::vector<GiNaC::ex> rho = residual_rows(eq, cm, rs);
    GiNaC::ex s = 0;
    for (size_t r = 0; r < rho.size(); ++r) s += mu[r] * rho[r];
    if (choice == HessianChoice::Auto) {
      const size_t terms = distinct_terms(s, kHessianTerms);
      if (terms > kHessianTerms) {
        hessian_note_ = fmt::format(
            "limited-memory Hessian: the equations have more than {} distinct terms, beyond "
            "which symbolic second derivatives cost more set-up than they save (--hessian exact "
            "forces them)",
            kHessianTerms);
        return;
      }
    }
    std::vector<GiNaC::symbol> in = base;
    std::vector<size_t> columns = state_columns;
    for (const std::vector<GiNaC::symbol>* group : {&rs.a, &rs.lambda})
      for (const GiNaC::symbol& x : *group) {
        columns.push_back(in.size());
        in.push_back(x);
      }
    in.push_back(rs.alpha);
    in.insert(in.end(), mu.begin(), mu.end());
    // The costliest tape of the solve (docs/theory.md §10, "Hessian"): on machine code once it
    // is had; later stages share it, and the compiler's run, with this one.
    auto made = std::make_shared<SecondDerivatives>(s, in, columns);
    made->use_machine_code(evaluation, machine_code);
    h_dae_ = std::move(made);
  }
  // w₀ L + w₁ Φ + w₂ M + Σ w_p g_p, over (q, v, u, λ) and, with T free, t = T (k + τ_j)/N.
  {
    const std::vector<GiNaC::symbol> w = numbered_symbols("hess_w", fun_.count());
    const std::vector<GiNaC::ex> fs = problem_functions(spec_);
    GiNaC::ex s = 0;
    for (size_t f = 0; f < fs.size(); ++f) s += w[f] * fs[f];
    std::vector<GiNaC::symbol> in = base;
    std::vector<size_t> columns = state_columns;
    for (const GiNaC::symbol& l : spec_.multipliers) {
      columns.push_back(in.size());
      in.push_back(l);
    }
    in.insert(in.end(), w.begin(), w.end());
    if (free_T_) columns.push_back(0);  // t, the tape's first input
    h_point_ = SecondDerivatives(s, in, columns);
  }
  // Σ ν_i C_i + Σ ν_{m+i} Ċ_i.
  if (m_ > 0 && !start_rows_.empty()) {
    const std::vector<GiNaC::symbol> nu = numbered_symbols("hess_nu", 2 * m_);
    GiNaC::ex s = 0;
    for (size_t k = 0; k < m_; ++k)
      s += nu[k] * out[cm.C_out() + k] + nu[m_ + k] * out[cm.Cdot_out() + k];
    std::vector<GiNaC::symbol> in = base;
    in.insert(in.end(), nu.begin(), nu.end());
    h_invariants_ = SecondDerivatives(
        s, in, std::vector<size_t>(state_columns.begin(), state_columns.begin() + nx_));
  }
  // The pattern: one walk, entries merged by position.
  std::vector<double> ones(rows_, 1.0);
  std::map<std::pair<size_t, size_t>, size_t> where;
  walk_hessian(guess_.data(), 1.0, ones.data(), [&](size_t r, size_t c, double) {
    auto [it, added] = where.emplace(std::make_pair(r, c), hnz_.size());
    if (added) hnz_.emplace_back(r, c);
    hslot_.push_back(it->second);
  });
  hessian_ready_ = true;
}

void Transcription::hessian(const double* x, double sigma, const double* y, double* values) {
  std::fill(values, values + hnz_.size(), 0.0);
  size_t e = 0;
  walk_hessian(x, sigma, y, [&](size_t, size_t, double v) { values[hslot_[e++]] += v; });
}

template <class Emit>
void Transcription::walk_hessian(const double* x, double sigma, const double* y, Emit&& emit) {
  const double T = horizon(x), h = T / N_;
  const size_t nr = nx_ + m_, nf = fun_.count();
  std::vector<Term> A, B;
  std::vector<double> g(nx_);
  // With T free (variable 0) a = v' = (1/h) Σ_l D_jl V_{k,l} carries −a/T and t = T (k + τ_j)/N
  // carries (k + τ_j)/N (docs/theory.md §10, "Hessian", free horizon).
  const auto on_T = [&](std::vector<Term>& t, double coefficient) {
    if (free_T_) t.push_back({0, coefficient});
  };
  // The point functions' local columns: q, v, u, λ, then t when T is free; the terminal point
  // is (N − 1, d), where τ_d = 1.
  const auto point_terms = [&](int k, int j, size_t col, std::vector<Term>& t) {
    t.clear();
    if (col < nx_ + nu_ + m_)
      t.push_back({point_variable(col + 1, k, j), 1.0});
    else
      on_T(t, (k + rad_.tau[static_cast<size_t>(j)]) / N_);
  };
  // At a kink (|x| at x = 0) the one-sided second derivatives (docs/theory.md §10, "Kinks").
  const auto scatter_all = [&](const SecondDerivatives& sd, auto&& terms) {
    hout_.resize(sd.pattern().size());
    analysis_detail::eval_off_kink(hin_.data() + cm_->q_offset(), nx_, hout_.data(),
                                   hout_.data() + hout_.size(), [&] { sd.eval(hin_, hout_); });
    for (size_t e = 0; e < sd.pattern().size(); ++e) {
      const auto [a, b] = sd.pattern()[e];
      terms(a, A);
      terms(b, B);
      scatter(a == b, A, B, hout_[e], emit);
    }
  };
  if (free_T_) evaluate_points(x);  // the T terms read ρ's and the integrand's derivatives
  for (int k = 0; k < N_; ++k)
    for (int j = 1; j <= d_; ++j) {
      const size_t p = static_cast<size_t>(k * d_ + j - 1);
      const double* X = state(x, k, j);
      collocation_derivative(x, k, j);
      // The DAE residual: inputs, a = v', λ, α, μ.
      hin_ = load(time(x, k, j), X, control(x, k, j));
      hin_.insert(hin_.end(), xp_.begin() + static_cast<long>(nq_), xp_.end());
      hin_.insert(hin_.end(), multipliers(x, k, j), multipliers(x, k, j) + m_);
      hin_.push_back(dyn_.baumgarte());
      hin_.insert(hin_.end(), y + p * nr, y + (p + 1) * nr);
      scatter_all(*h_dae_,
                  [&](size_t col, std::vector<Term>& t) { residual_terms(x, k, j, col, t); });
      if (free_T_) {
        // x' = (1/h) Σ_l D_jl X_l is not linear in T: with g = Σ μ ∂r/∂x' (μ_q for q', Mμ_v + Gᵀμ_λ
        // for v'), ∂²x'/∂T² = 2x'/T² and ∂²x'/∂T∂X_l = −D_jl/(hT).
        const double* rho = point_rho(p);
        std::copy(y + p * nr, y + p * nr + nq_, g.begin());
        std::fill(g.begin() + static_cast<long>(nq_), g.end(), 0.0);
        for (size_t e = 0; e < dae_->pattern().size(); ++e) {  // ∂ρ/∂a: M and G
          const auto [row, col] = dae_->pattern()[e];
          if (col >= nx_ + nu_ && col < nx_ + nu_ + nv_)
            g[nq_ + col - nx_ - nu_] += y[p * nr + row] * rho[nr + e];
        }
        for (size_t i = 0; i < nx_; ++i) {
          emit(0, 0, g[i] * 2 * xp_[i] / (T * T));
          for (int l = 0; l <= d_; ++l)
            emit(xi(k, l) + i, 0, -g[i] * rad_.derivative(j, l) / (h * T));
        }
      }
      // The integrand (Radau weight) and the path constraints.
      const double wL = sigma * sign_ * h * rad_.b[static_cast<size_t>(j - 1)];
      hin_ = load(time(x, k, j), X, control(x, k, j));
      hin_.insert(hin_.end(), multipliers(x, k, j), multipliers(x, k, j) + m_);
      hin_.push_back(wL);                                                       // L
      hin_.push_back(0.0);                                                      // Φ
      hin_.push_back(sigma * sign_ * rad_.b[static_cast<size_t>(j - 1)] / N_);  // M
      for (size_t i = 0; i < np_; ++i) hin_.push_back(y[path_rows_ + p * np_ + i]);
      scatter_all(h_point_, [&](size_t col, std::vector<Term>& t) { point_terms(k, j, col, t); });
      if (free_T_) {
        // The integrand's weight h b_j = T b_j/N is linear in T: ∂²/∂T∂z of wL·L is (wL/T)·∂L/∂z.
        const double* out = point_fun(p);
        const double dt = (k + rad_.tau[static_cast<size_t>(j)]) / N_;
        for (size_t e = 0; e < fun_.pattern().size(); ++e) {
          const auto [f, c] = fun_.pattern()[e];
          if (f != kIntegrand) continue;
          const double v = wL / T * out[nf + e];
          if (c == 0)
            emit(0, 0, 2 * v * dt);
          else
            emit(point_variable(c, k, j), 0, v);
        }
      }
    }
  // The terminal term at (T, X_{N,0}, U_{N−1} (a polynomial control: U_{N−1,d}), Λ_{N−1,d}).
  hin_ = load(T, state(x, N_, 0), control(x, N_ - 1, d_));
  hin_.insert(hin_.end(), multipliers(x, N_ - 1, d_), multipliers(x, N_ - 1, d_) + m_);
  hin_.push_back(0.0);            // L
  hin_.push_back(sigma * sign_);  // Φ
  hin_.push_back(0.0);            // M
  hin_.resize(hin_.size() + np_, 0.0);
  scatter_all(h_point_, [&](size_t col, std::vector<Term>& t) { point_terms(N_ - 1, d_, col, t); });
  // The tracking term's diagonal (docs/theory.md §10, "Homotopy").
  if (track_ > 0)
    for_each_node([&](size_t at) {
      for (size_t i = 0; i < nx_; ++i) emit(at + i, at + i, sigma * 2 * track_ * track_scale_[i]);
    });
  // A periodic orientation's y·(AᵀB − BᵀA)_ij/2 (A = R(0), B = R(T)): ∂²/∂A_ai∂B_aj = y/2 and
  // ∂²/∂A_aj∂B_ai = −y/2 (docs/theory.md §10, "Free bodies").
  const size_t turning_at = rows_ - turning_.size();
  for (size_t r = 0; r < turning_.size(); ++r) {
    const auto [base, w] = turning_[r];
    const auto [i, j] = kSkewPairs[w];
    const size_t A = xi(0, 0) + base, B = xi(N_, 0) + base;
    for (size_t a = 0; a < 3; ++a) {
      emit(B + 3 * a + j, A + 3 * a + i, y[turning_at + r] / 2);
      emit(B + 3 * a + i, A + 3 * a + j, -y[turning_at + r] / 2);
    }
  }
  // The invariants imposed at t = 0, on X_{0,0}.
  if (start_rows_.empty()) return;
  const size_t at = path_rows_ + static_cast<size_t>(N_ * d_) * np_;
  // A free body's ν (RᵀR − 1)_ij: ∂²/∂R_ai∂R_aj = ν for i ≠ j, 2ν on the diagonal (§10, "Free
  // bodies").
  for (size_t r = 0; r < start_rows_.size(); ++r) {
    if (start_rows_[r] < 2 * m_) continue;
    const size_t w = start_rows_[r] - 2 * m_, base = xi(0, 0) + rotations_[w / 6];
    const auto [i, j] = kOrthonormalPairs[w % 6];
    for (size_t a = 0; a < 3; ++a)
      emit(base + 3 * a + j, base + 3 * a + i, (i == j ? 2.0 : 1.0) * y[at + r]);
  }
  if (m_ == 0) return;
  hin_ = load(0.0, state(x, 0, 0), control(x, 0, 0));
  std::vector<double> nu(2 * m_, 0.0);
  for (size_t r = 0; r < start_rows_.size(); ++r)
    if (start_rows_[r] < 2 * m_) nu[start_rows_[r]] = y[at + r];
  hin_.insert(hin_.end(), nu.begin(), nu.end());
  scatter_all(h_invariants_,
              [&](size_t col, std::vector<Term>& t) { residual_terms(x, 0, 0, col, t); });
}

}  // namespace lagrange::collocation
