// docs/theory.md §4.8: D = M, c_ijk = ½(∂d_kj/∂qᵢ + ∂d_ki/∂qⱼ − ∂d_ij/∂q_k), C_kj = Σᵢ c_ijk q̇ᵢ,
// g_k = ∂U/∂q_k, checked against the derived forcing h = −C q̇ − g.

#include <fmt/format.h>

#include <random>
#include <sstream>
#include <stdexcept>

#include "lagrange/manipulator.hpp"
#include "symbolic/expansion_bound.hpp"
#include "symbolic/memo_diff.hpp"
#include "symbolic/point_value.hpp"
#include "symbolic/printed_size.hpp"

namespace lagrange {

namespace {

using symbolic::printed_size;

/// A product with a negative numeric factor (−q1, −2 q).
bool negative_multiple(const GiNaC::ex& e) {
  if (!GiNaC::is_a<GiNaC::mul>(e)) return false;
  for (size_t i = 0; i < e.nops(); ++i)
    if (GiNaC::is_a<GiNaC::numeric>(e.op(i)) && GiNaC::ex_to<GiNaC::numeric>(e.op(i)).is_negative())
      return true;
  return false;
}

// cos(a + b) = cos a cos b − sin a sin b, sin(a + b) = sin a cos b + cos a sin b, recursively.
// A negative multiple comes out of the argument: cos(−x) = cos x, sin(−x) = −sin x.
struct ExpandTrig : GiNaC::map_function {
  GiNaC::ex operator()(const GiNaC::ex& e) override {
    const GiNaC::ex m = e.map(*this);
    if (!GiNaC::is_a<GiNaC::function>(m)) return m;
    const std::string name = GiNaC::ex_to<GiNaC::function>(m).get_name();
    if (name != "sin" && name != "cos") return m;
    if (negative_multiple(m.op(0)))
      return name == "cos" ? GiNaC::cos(-m.op(0)) : -GiNaC::sin(-m.op(0));
    if (!GiNaC::is_a<GiNaC::add>(m.op(0))) return m;
    const GiNaC::ex a = m.op(0).op(0), b = m.op(0) - a;
    const GiNaC::ex sa = (*this)(GiNaC::sin(a)), ca = (*this)(GiNaC::cos(a));
    const GiNaC::ex sb = (*this)(GiNaC::sin(b)), cb = (*this)(GiNaC::cos(b));
    return name == "cos" ? ca * cb - sa * sb : sa * cb + ca * sb;
  }
};

/// Small expressions in the shorter of their derived and trig-simplified forms (big arms' entries
/// are left as derived).
GiNaC::ex tidy(const GiNaC::ex& e) {
  if (!symbolic::expands_within(e, 2000)) return e;  // no unbounded expansion (asked first:
  const size_t size = printed_size(e);               // linear in the DAG, where printing is not)
  if (size > 4000) return e;
  const GiNaC::ex s = trig_simplify(e);
  return printed_size(s) < size ? s : e;
}

/// Evaluates expressions at two random points (parameters in [0.5, 1.5], coordinates,
/// velocities, t and inputs in [−2, 2]) with 40 digits, memoised over the expressions' shared
/// subtrees: symbolic zeros come out below 1e-25.
class Probe {
 public:
  explicit Probe(const Equations& eq) {
    const Model& m = *eq.model;
    std::mt19937 rng(20261122);
    std::uniform_int_distribution<int> draw(-2000, 2000);
    auto rational = [&](int lo) { return GiNaC::numeric(draw(rng) + lo, 1000); };
    for (int p = 0; p < 2; ++p) {
      GiNaC::exmap v;
      for (const Parameter& par : m.parameters)
        v[par.sym] = GiNaC::abs(rational(0)) / 2 + GiNaC::numeric(1, 2);
      for (size_t i = 0; i < eq.nv; ++i) {
        v[eq.kin.q[i]] = rational(0);
        v[eq.kin.v[i]] = rational(0);
      }
      v[m.t] = rational(0);
      for (const Input& u : m.inputs) {
        v[u.u] = rational(0);
        v[u.ud] = rational(0);
        v[u.udd] = rational(0);
      }
      points_.emplace_back(std::move(v));
    }
  }
  bool zero(const GiNaC::ex& e) {
    const long saved = GiNaC::Digits;
    GiNaC::Digits = 40;
    bool all = true;
    for (symbolic::PointValue& value : points_)
      if (!(GiNaC::abs(value(e)).to_double() < 1e-25)) all = false;
    GiNaC::Digits = saved;
    return all;
  }

 private:
  std::vector<symbolic::PointValue> points_;
};

/// J_v = ∂r_c/∂q of the centre of mass r_c = r + R c, and J_ω with column j = unskew(∂R/∂q_j Rᵀ)
/// (Ṙ Rᵀ = [ω]× in world axes).
LinkJacobian link_jacobian(const Body& b, const Kinematics& kin) {
  const size_t n = kin.plain;
  LinkJacobian J{b.name, GiNaC::matrix(3, n), GiNaC::matrix(3, n)};
  const Vec3 rc = b.world_point(b.com);
  for (size_t j = 0; j < n; ++j) {
    const GiNaC::symbol& q = kin.q[j];
    GiNaC::matrix S(3, 3);
    for (size_t a = 0; a < 3; ++a)
      for (size_t c = 0; c < 3; ++c) {
        GiNaC::ex e = 0;
        for (size_t k = 0; k < 3; ++k) e += b.rotation[a][k].diff(q) * b.rotation[c][k];
        S(a, c) = e;
      }
    const GiNaC::ex w[3] = {S(2, 1), S(0, 2), S(1, 0)};
    for (size_t a = 0; a < 3; ++a) {
      J.Jv(a, j) = tidy(rc[a].diff(q));
      J.Jw(a, j) = tidy(w[a]);
    }
  }
  return J;
}

}  // namespace

GiNaC::ex trig_simplify(const GiNaC::ex& e) {
  ExpandTrig expand;
  return simplify(expand(e));
}

ManipulatorForm manipulator_form(const Equations& eq) {
  const Model& m = *eq.model;
  if (eq.m > 0)
    throw std::invalid_argument(
        fmt::format("the manipulator form needs an unconstrained model, got {} constraints", eq.m));
  if (eq.kin.plain != eq.nv || eq.nq != eq.nv)
    throw std::invalid_argument(
        "the manipulator form needs plain coordinates only, got a free body (its R and omega are "
        "not joint coordinates)");
  const size_t n = eq.nv;
  ManipulatorForm f;
  f.eq = &eq;
  f.D = GiNaC::matrix(n, n);
  f.C = GiNaC::matrix(n, n);
  std::vector<GiNaC::symbol> moving{m.t};
  for (const Input& u : m.inputs) moving.insert(moving.end(), {u.u, u.ud, u.udd});
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j) {
      for (const GiNaC::symbol& s : moving)
        if (eq.M(i, j).has(s))
          throw std::invalid_argument(fmt::format(
              "the manipulator form needs D(q) of the coordinates and parameters only, got D_{}{} "
              "depending on {}",
              i + 1, j + 1, s.get_name()));
      f.D(i, j) = j < i ? f.D(j, i) : tidy(eq.M(i, j));
    }
  Probe probe(eq);
  // c_ijk = c_jik, computed for i ≤ j.
  // dD[l] = ∂D/∂q_l, differentiated on the upper triangle and mirrored (D is symmetric), each
  // shared subexpression once (the entries of a long chain's D share most of their terms).
  symbolic::MemoDiff differentiate(
      std::vector<GiNaC::symbol>(eq.kin.q.begin(), eq.kin.q.begin() + n));
  std::vector<GiNaC::matrix> dD(n, GiNaC::matrix(n, n));
  for (size_t l = 0; l < n; ++l)
    for (size_t i = 0; i < n; ++i)
      for (size_t j = i; j < n; ++j) dD[l](i, j) = dD[l](j, i) = differentiate.diff(f.D(i, j), l);
  std::vector<GiNaC::ex> c(n * n * n, 0);
  for (size_t k = 0; k < n; ++k)
    for (size_t i = 0; i < n; ++i)
      for (size_t j = i; j < n; ++j) {
        GiNaC::ex v = (dD[i](k, j) + dD[j](k, i) - dD[k](i, j)) / 2;
        v = probe.zero(v) ? GiNaC::ex(0) : tidy(v);
        c[(i * n + j) * n + k] = c[(j * n + i) * n + k] = v;
      }
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j)
      for (size_t k = 0; k < n; ++k)
        if (!c[(i * n + j) * n + k].is_zero())
          f.christoffel.push_back({i, j, k, c[(i * n + j) * n + k]});
  for (size_t k = 0; k < n; ++k)
    for (size_t j = 0; j < n; ++j) {
      GiNaC::ex s = 0;
      for (size_t i = 0; i < n; ++i) s += c[(i * n + j) * n + k] * eq.kin.v[i];
      f.C(k, j) = s;
    }
  for (size_t k = 0; k < n; ++k) {
    f.g.push_back(tidy(differentiate.diff(eq.U, k)));
    f.tau.push_back(eq.Q[k]);
    GiNaC::ex residual = eq.h[k] + f.g[k];
    for (size_t j = 0; j < n; ++j) residual += f.C(k, j) * eq.kin.v[j];
    if (!probe.zero(residual))
      throw std::invalid_argument(fmt::format(
          "the manipulator form needs forcing h = -C(q, q_dot) q_dot - g(q), got other terms in "
          "the equation of {} (a kinetic energy linear in the velocities, a moving base, forces "
          "outside the potential)",
          eq.kin.q_names[k]));
  }
  for (const Body& b : m.bodies)
    if (!b.free) f.jacobians.push_back(link_jacobian(b, eq.kin));
  return f;
}

GiNaC::matrix d_dot_minus_2c(const ManipulatorForm& f) {
  const Equations& eq = *f.eq;
  const size_t n = eq.nv;
  GiNaC::matrix N(n, n);
  for (size_t k = 0; k < n; ++k)
    for (size_t j = 0; j < n; ++j) {
      GiNaC::ex ddot = 0;
      for (size_t i = 0; i < n; ++i) ddot += f.D(k, j).diff(eq.kin.q[i]) * eq.kin.v[i];
      N(k, j) = ddot - 2 * f.C(k, j);
    }
  return N;
}

}  // namespace lagrange
