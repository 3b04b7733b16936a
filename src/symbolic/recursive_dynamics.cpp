// The recursive formulation (docs/theory.md §4.9): Featherstone's articulated-body algorithm on
// the model's joint tree, written out symbolically. Every intermediate quantity of a link is
// named (Equations::definitions), so the equations grow linearly with the number of links and
// structural zeros (planar chains, axes along a frame axis) drop out before anything is compiled.

#include <fmt/format.h>

#include <stdexcept>
#include <string>
#include <unordered_set>
#include <vector>

#include "lagrange/equations.hpp"
#include "lagrange/error.hpp"
#include "model/expression_algebra.hpp"
#include "model/vec3_algebra.hpp"
#include "symbolic/mechanical_terms.hpp"
#include "symbolic/time_partials.hpp"

namespace lagrange {

namespace {

using GiNaC::ex;
using Kind = TreeJoint::Kind;
using model::cross;
using model::mat_mul;
using model::mat_t_vec;
using model::mat_vec;
using symbolic::dot;

/// A spatial motion vector: angular part, and linear velocity (or acceleration) of the point at
/// the frame origin.
struct Motion {
  Vec3 w{0, 0, 0}, v{0, 0, 0};
};
/// A spatial force: moment about the frame origin, and force.
struct Force {
  Vec3 n{0, 0, 0}, f{0, 0, 0};
};
/// A spatial inertia [[A, B], [Bᵀ, C]] about the frame origin, A and C symmetric.
struct Inertia {
  Mat3 A, B, C;
};

const Mat3 kZero{Vec3{0, 0, 0}, Vec3{0, 0, 0}, Vec3{0, 0, 0}};

Vec3 plus(const Vec3& a, const Vec3& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
Vec3 scaled(const Vec3& a, const ex& s) {
  return {a[0] * s, a[1] * s, a[2] * s};
}
/// X ± Y, x yᵀ s, and the cross-product matrix p̂ (p̂ x = p × x).
Mat3 sum(const Mat3& X, const Mat3& Y, int sign = 1) {
  Mat3 Z;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) Z[i][j] = X[i][j] + sign * Y[i][j];
  return Z;
}
Mat3 outer(const Vec3& x, const Vec3& y, const ex& s) {
  Mat3 Z;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) Z[i][j] = x[i] * y[j] * s;
  return Z;
}
Mat3 hat(const Vec3& p) {
  return {Vec3{0, -p[2], p[1]}, Vec3{p[2], 0, -p[0]}, Vec3{-p[1], p[0], 0}};
}

/// Names intermediate values: every expression that is not a number or a symbol becomes a fresh
/// symbol defined by it (Equations::definitions), so later expressions stay small.
class Definitions {
 public:
  explicit Definitions(std::vector<std::pair<GiNaC::symbol, ex>>& out) : out_(out) {}

  ex name(const ex& e, const std::string& what) {
    if (GiNaC::is_a<GiNaC::numeric>(e) || GiNaC::is_a<GiNaC::symbol>(e)) return e;
    GiNaC::symbol s(what);
    out_.emplace_back(s, e);
    return s;
  }
  Vec3 name(const Vec3& x, const std::string& what) {
    return {name(x[0], what + "x"), name(x[1], what + "y"), name(x[2], what + "z")};
  }
  /// A symmetric matrix: the upper triangle named, the lower mirrored.
  Mat3 name_symmetric(const Mat3& X, const std::string& what) {
    Mat3 Z;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = i; j < 3; ++j)
        Z[i][j] = Z[j][i] = name(X[i][j], fmt::format("{}{}{}", what, i + 1, j + 1));
    return Z;
  }
  Mat3 name(const Mat3& X, const std::string& what) {
    Mat3 Z;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        Z[i][j] = name(X[i][j], fmt::format("{}{}{}", what, i + 1, j + 1));
    return Z;
  }
  Inertia name(const Inertia& I, const std::string& what) {
    return {name_symmetric(I.A, what + "A"), name(I.B, what + "B"),
            name_symmetric(I.C, what + "C")};
  }

 private:
  std::vector<std::pair<GiNaC::symbol, ex>>& out_;
};

/// The spatial inertia of a body about its frame origin: A = I_c + m(|c|²1 − c cᵀ), B = m ĉ,
/// C = m 1 (docs/theory.md §4.9).
Inertia body_inertia(const Body& b) {
  const Vec3& c = b.com;
  const ex cc = dot(c, c);
  Inertia I{b.inertia, hat(scaled(c, b.mass)), kZero};
  for (size_t i = 0; i < 3; ++i) {
    I.C[i][i] = b.mass;
    for (size_t j = 0; j < 3; ++j) I.A[i][j] += b.mass * ((i == j ? cc : ex(0)) - c[i] * c[j]);
  }
  return I;
}

/// I V and the bias force V ×* (I V).
Force momentum(const Inertia& I, const Motion& V) {
  return {plus(mat_vec(I.A, V.w), mat_vec(I.B, V.v)), plus(mat_t_vec(I.B, V.w), mat_vec(I.C, V.v))};
}
Force bias_force(const Motion& V, const Force& h) {
  return {plus(cross(V.w, h.n), cross(V.v, h.f)), cross(V.w, h.f)};
}

/// A motion of the parent frame seen in the link frame: (Rᵀω, Rᵀ(v + ω × p)).
Motion to_child(const TreeJoint& j, const Motion& m) {
  return {mat_t_vec(j.rotation, m.w), mat_t_vec(j.rotation, plus(m.v, cross(m.w, j.origin)))};
}
/// A force of the link frame seen in the parent frame: (R n + p × R f, R f).
Force to_parent(const TreeJoint& j, const Force& F) {
  const Vec3 f = mat_vec(j.rotation, F.f);
  return {plus(mat_vec(j.rotation, F.n), cross(j.origin, f)), f};
}
/// Xᵀ I X for the motion transform X parent → link: with A_r = R A Rᵀ (likewise B, C),
/// A' = A_r − B_r p̂ + p̂ B_rᵀ − p̂ C_r p̂, B' = B_r + p̂ C_r, C' = C_r.
Inertia to_parent(const TreeJoint& j, const Inertia& I) {
  const Mat3& R = j.rotation;
  const Mat3 Rt = model::transpose(R);
  const Mat3 Ar = mat_mul(mat_mul(R, I.A), Rt), Br = mat_mul(mat_mul(R, I.B), Rt),
             Cr = mat_mul(mat_mul(R, I.C), Rt);
  const Mat3 P = hat(j.origin);
  const Mat3 PC = mat_mul(P, Cr);
  return {
      sum(sum(Ar, mat_mul(Br, P), -1), sum(mat_mul(P, model::transpose(Br)), mat_mul(PC, P), -1)),
      sum(Br, PC), Cr};
}

/// The joint's motion subspace S: (k, 0) revolute, (0, k) prismatic; and Sᵀ of a force.
Motion subspace(const TreeJoint& j, const ex& rate) {
  if (j.kind == Kind::Revolute) return {scaled(j.axis, rate), {0, 0, 0}};
  return {{0, 0, 0}, scaled(j.axis, rate)};
}
ex along(const TreeJoint& j, const Force& F) {
  return dot(j.axis, j.kind == Kind::Revolute ? F.n : F.f);
}
ex along(const Force& U, const Motion& a) {
  return dot(U.n, a.w) + dot(U.f, a.v);
}

/// The symbols of expressions, visiting each node of the expression DAG once (a chain's poses
/// share their parents' entries, so the tree behind them is exponentially larger). Visited
/// nodes are kept alive: op() of a sum or product may build temporaries, whose addresses would
/// otherwise be reused.
class SymbolCollector {
 public:
  void add(const ex& e) {
    if (!seen_.insert(&GiNaC::ex_to<GiNaC::basic>(e)).second) return;
    alive_.push_back(e);
    if (GiNaC::is_a<GiNaC::symbol>(e)) {
      used_.insert(e);
      return;
    }
    for (size_t k = 0; k < e.nops(); ++k) add(e.op(k));
  }
  bool used(const GiNaC::symbol& s) const { return used_.count(s) > 0; }

 private:
  GiNaC::exset used_;
  std::unordered_set<const GiNaC::basic*> seen_;
  std::vector<ex> alive_;
};

/// Drops the definitions that neither q̈ nor T and U read (the root link's articulated inertia,
/// which no parent takes), so that what `derive --form recursive` prints is what is computed.
void keep_used_definitions(Equations& eq) {
  SymbolCollector symbols;
  for (const ex& a : eq.h) symbols.add(a);
  symbols.add(eq.T);
  symbols.add(eq.U);
  std::vector<bool> keep(eq.definitions.size(), false);
  for (size_t k = eq.definitions.size(); k-- > 0;) {
    if (!symbols.used(eq.definitions[k].first)) continue;
    keep[k] = true;
    symbols.add(eq.definitions[k].second);
  }
  std::vector<std::pair<GiNaC::symbol, ex>> kept;
  for (size_t k = 0; k < keep.size(); ++k)
    if (keep[k]) kept.push_back(std::move(eq.definitions[k]));
  eq.definitions = std::move(kept);
}

}  // namespace

std::string recursive_unsuitable(const Model& model) {
  if (model.tree.empty()) return "it has no joint tree (links: or urdf:)";
  if (!model.constraints.empty()) return "it has constraints";
  if (!model.particles.empty()) return "it has particles";
  if (!model.kinetic.is_zero()) return "it has a written kinetic energy";
  if (!model.torques.empty()) return "it has torques on bodies";
  std::vector<int> joint_of(model.coordinates.size(), -1), body_of(model.bodies.size(), -1);
  for (size_t i = 0; i < model.tree.size(); ++i) {
    const TreeJoint& j = model.tree[i];
    if (j.parent >= static_cast<int>(i)) return "its joint tree lists a child before its parent";
    if (j.coordinate >= 0) joint_of.at(static_cast<size_t>(j.coordinate)) = static_cast<int>(i);
    if (j.body >= 0) body_of.at(static_cast<size_t>(j.body)) = static_cast<int>(i);
  }
  for (size_t c = 0; c < joint_of.size(); ++c)
    if (joint_of[c] < 0)
      return fmt::format("coordinate '{}' is not a joint of its tree", model.coordinates[c].name);
  for (size_t b = 0; b < body_of.size(); ++b)
    if (body_of[b] < 0)
      return fmt::format("body '{}' is not a link of its tree", model.bodies[b].name);
  return "";
}

namespace symbolic {

// docs/theory.md §4.9, the articulated-body algorithm in link frames:
//   outward:  V = X V_p + S q̇,  c = V ×ₘ S q̇,  p = V ×* (I V) (its own inertia, bias force);
//   inward:   U = Iᴬ S, D = Sᵀ U, u = τ − Sᵀ pᴬ, Iᵃ = Iᴬ − U Uᵀ/D, pᵃ = pᴬ + Iᵃ c + U u/D,
//             Iᴬ_p += Xᵀ Iᵃ X, pᴬ_p += Xᵀ pᵃ;
//   outward:  a' = X a_p + c (a₀ = (0, −g)),  q̈ = (u − Uᵀ a')/D,  a = a' + S q̈.
// τ collects everything the tree does not: joint forces, forces and dampers by virtual work,
// springs and written potentials by −∂U/∂q (§4.1, §4.2).
void add_recursive_terms(const Kinematics& kin, Equations& eq) {
  const Model& model = *kin.model;
  const size_t n = model.tree.size();
  Definitions defs(eq.definitions);
  MechanicalTerms forces(kin.v.size());
  add_energy_terms(kin, forces);
  add_generalized_forces(kin, forces);

  std::vector<Motion> V(n), c(n), acc(n);
  std::vector<Inertia> IA(n);
  std::vector<Force> pA(n);
  std::vector<Force> U(n);
  std::vector<ex> invD(n), u(n);
  eq.pivots.assign(kin.v.size(), 1);
  GiNaC::ex T = 0;
  for (size_t i = 0; i < n; ++i) {
    const TreeJoint& j = model.tree[i];
    const std::string at = fmt::format("L{}.", i + 1);
    const Motion parent = j.parent < 0 ? Motion{} : V[static_cast<size_t>(j.parent)];
    Motion Vi = to_child(j, parent);
    if (j.kind != Kind::Fixed) {
      const ex qd = kin.v[static_cast<size_t>(j.coordinate)];
      const Motion s = subspace(j, qd);
      Vi = {plus(Vi.w, s.w), plus(Vi.v, s.v)};
      // c = V ×ₘ S q̇ = (ω × s_w, ω × s_v + v × s_w)
      c[i] = {defs.name(cross(Vi.w, s.w), at + "c_w"),
              defs.name(plus(cross(Vi.w, s.v), cross(Vi.v, s.w)), at + "c_v")};
    }
    V[i] = {defs.name(Vi.w, at + "w"), defs.name(Vi.v, at + "v")};
    IA[i] = {kZero, kZero, kZero};
    if (j.body >= 0) {
      IA[i] = body_inertia(model.bodies[static_cast<size_t>(j.body)]);
      const Force h = momentum(IA[i], V[i]);
      T += (dot(V[i].w, h.n) + dot(V[i].v, h.f)) / 2;
      pA[i] = bias_force(V[i], h);
    }
  }
  for (size_t i = n; i-- > 0;) {
    const TreeJoint& j = model.tree[i];
    const std::string at = fmt::format("L{}.", i + 1);
    Inertia Ia = defs.name(IA[i], at + "I");
    Force pa{defs.name(pA[i].n, at + "p_n"), defs.name(pA[i].f, at + "p_f")};
    if (j.kind != Kind::Fixed) {
      const auto qi = static_cast<size_t>(j.coordinate);
      const Force Ui = j.kind == Kind::Revolute
                           ? Force{mat_vec(Ia.A, j.axis), mat_t_vec(Ia.B, j.axis)}
                           : Force{mat_vec(Ia.B, j.axis), mat_vec(Ia.C, j.axis)};
      U[i] = {defs.name(Ui.n, at + "U_w"), defs.name(Ui.f, at + "U_v")};
      const ex D = defs.name(along(j, U[i]), at + "D");
      if (D.is_zero()) {
        // A point mass on its own joint axis: the pivot is zero for every state and parameter.
        const Coordinate& coordinate = model.coordinates[qi];
        throw ModelError(coordinate.loc,
                         fmt::format("coordinate '{}' has no inertia at the initial state (nor "
                                     "at any other): the links its joint carries have none about "
                                     "its axis (articulated-body pivot D = 0, docs/theory.md "
                                     "§4.9); expected positive masses and non-zero lengths",
                                     coordinate.name));
      }
      eq.pivots[qi] = D;
      invD[i] = defs.name(1 / D, at + "invD");
      u[i] = defs.name(forces.h[qi] + forces.Q[qi] - along(j, pa), at + "u");
      Ia = defs.name(Inertia{sum(Ia.A, outer(U[i].n, U[i].n, invD[i]), -1),
                             sum(Ia.B, outer(U[i].n, U[i].f, invD[i]), -1),
                             sum(Ia.C, outer(U[i].f, U[i].f, invD[i]), -1)},
                     at + "Ia");
      const Force Ic = momentum(Ia, c[i]);
      pa = {defs.name(plus(plus(pa.n, Ic.n), scaled(U[i].n, u[i] * invD[i])), at + "pa_n"),
            defs.name(plus(plus(pa.f, Ic.f), scaled(U[i].f, u[i] * invD[i])), at + "pa_f")};
    }
    if (j.parent < 0) continue;
    const auto p = static_cast<size_t>(j.parent);
    const Inertia up = to_parent(j, Ia);
    IA[p] = {sum(IA[p].A, up.A), sum(IA[p].B, up.B), sum(IA[p].C, up.C)};
    const Force fp = to_parent(j, pa);
    pA[p] = {plus(pA[p].n, fp.n), plus(pA[p].f, fp.f)};
  }
  const Vec3 g = model.gravity.value_or(Vec3{0, 0, 0});
  const Motion base{{0, 0, 0}, scaled(g, -1)};
  eq.h.assign(kin.v.size(), 0);
  for (size_t i = 0; i < n; ++i) {
    const TreeJoint& j = model.tree[i];
    const std::string at = fmt::format("L{}.", i + 1);
    const Motion x = to_child(j, j.parent < 0 ? base : acc[static_cast<size_t>(j.parent)]);
    Motion a{plus(x.w, c[i].w), plus(x.v, c[i].v)};
    if (j.kind != Kind::Fixed) {
      a = {defs.name(a.w, at + "a'_w"), defs.name(a.v, at + "a'_v")};
      const ex qdd = defs.name((u[i] - along(U[i], a)) * invD[i], at + "qdd");
      eq.h[static_cast<size_t>(j.coordinate)] = qdd;
      const Motion s = subspace(j, qdd);
      a = {plus(a.w, s.w), plus(a.v, s.v)};
    }
    acc[i] = {defs.name(a.w, at + "a_w"), defs.name(a.v, at + "a_v")};
  }
  // Energies for the observables: T from the link velocities above, U from the bodies' poses.
  GiNaC::ex U_gravity = 0;
  for (const Body& b : model.bodies) U_gravity -= b.mass * dot(g, b.world_point(b.com));
  eq.T = T;
  eq.U = forces.U + U_gravity;
  keep_used_definitions(eq);
}

}  // namespace symbolic

}  // namespace lagrange
