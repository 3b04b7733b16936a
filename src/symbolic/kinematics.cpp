#include "lagrange/equations.hpp"

namespace lagrange {

namespace {

// Ω = ω×, the skew matrix with Ω p = ω × p.
Mat3 skew(const Vec3& w) {
  return {Vec3{0, -w[2], w[1]}, Vec3{w[2], 0, -w[0]}, Vec3{-w[1], w[0], 0}};
}

// docs/theory.md §4.4: Ξ = (γ/2)((RᵀR)⁻¹ − 1), with (RᵀR)⁻¹ = adj(S)/det(S) for S = RᵀR.
Mat3 drift_correction(const Mat3& R, const GiNaC::ex& gamma) {
  Mat3 S;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      S[i][j] = R[0][i] * R[0][j] + R[1][i] * R[1][j] + R[2][i] * R[2][j];
  Mat3 adj;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) {
      const size_t r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
      adj[i][j] = S[r0][c0] * S[r1][c1] - S[r0][c1] * S[r1][c0];  // cofactor (j, i)
    }
  const GiNaC::ex det = S[0][0] * adj[0][0] + S[0][1] * adj[1][0] + S[0][2] * adj[2][0];
  Mat3 X;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) X[i][j] = gamma / 2 * (adj[i][j] / det - (i == j ? 1 : 0));
  return X;
}

}  // namespace

Kinematics kinematics(const Model& model) {
  Kinematics k;
  k.model = &model;
  for (const auto& c : model.coordinates) {
    k.q.push_back(c.q);
    k.q_names.push_back(c.name);
  }
  for (const auto& c : model.coordinates) {
    k.v.push_back(c.v);
    k.a.push_back(c.a);
    k.v_names.push_back(c.name + "_dot");
    k.qdot.push_back(c.v);
  }
  k.plain = model.coordinates.size();
  const char* axes[3] = {"x", "y", "z"};
  for (const auto& b : model.bodies) {
    if (!b.free) continue;
    k.has_gamma = true;
    for (size_t i = 0; i < 3; ++i) {
      k.q.push_back(b.r[i]);
      k.q_names.push_back(b.name + "." + axes[i]);
      k.qdot.push_back(b.rd[i]);
    }
    const Mat3 R = b.rot();
    const Mat3 W = skew({b.w[0], b.w[1], b.w[2]});
    const Mat3 X = drift_correction(R, k.gamma);
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) {
        k.q.push_back(b.R[3 * i + j]);
        k.q_names.push_back(b.name + ".R" + std::to_string(i + 1) + std::to_string(j + 1));
        GiNaC::ex e = 0;  // Ṙ = R(Ω + Ξ)
        for (size_t l = 0; l < 3; ++l) e += R[i][l] * (W[l][j] + X[l][j]);
        k.qdot.push_back(e);
      }
    for (size_t i = 0; i < 3; ++i) {
      k.v.push_back(b.rd[i]);
      k.a.push_back(b.rdd[i]);
      k.v_names.push_back(b.name + ".v" + axes[i]);
    }
    for (size_t i = 0; i < 3; ++i) {
      k.v.push_back(b.w[i]);
      k.a.push_back(b.wd[i]);
      k.v_names.push_back(b.name + ".w" + axes[i]);
    }
  }
  k.K.resize(k.v.size());
  for (size_t col = 0; col < k.v.size(); ++col) {
    if (col < k.plain) {
      k.K[col].emplace_back(col, GiNaC::ex(1));
      continue;
    }
    for (size_t j = k.plain; j < k.q.size(); ++j)
      if (k.qdot[j].has(k.v[col])) k.K[col].emplace_back(j, k.qdot[j].diff(k.v[col]));
  }
  k.K_rows.resize(k.q.size());
  for (size_t col = 0; col < k.K.size(); ++col)
    for (const auto& [j, kjk] : k.K[col]) k.K_rows[j].emplace_back(col, kjk);
  for (size_t j = 0; j < k.q.size(); ++j) k.role.emplace(k.q[j], std::make_pair('q', j));
  for (size_t i = 0; i < k.v.size(); ++i) {
    k.role.emplace(k.v[i], std::make_pair('v', i));
    k.role.emplace(k.a[i], std::make_pair('a', i));
  }
  return k;
}

}  // namespace lagrange
