// `lagrange export --c DIR --jacobian`: the exact derivatives ∂a/∂q, ∂a/∂v, ∂a/∂u of the
// exported forward dynamics as C99, with their sparsity (docs/theory.md §5.7).

#include <fmt/format.h>

#include <algorithm>
#include <numeric>

#include "io/export_c_common.hpp"
#include "lagrange/analysis.hpp"
#include "lagrange/io.hpp"

namespace lagrange {

namespace {

// What a derivative entry adds to the right-hand side of the differentiated KKT system
// (DynamicsJacobian::evaluate; docs/theory.md §5.1), in the generated code's switch.
enum Kind { kMass = 0, kForce, kConstraintRow, kBias, kRate, kValue };

struct Entry {
  int kind, i, j, col;
};

std::vector<Entry> entries(const DynamicsJacobian& jac) {
  const CompiledModel& c = jac.model();
  std::vector<Entry> out;
  for (const auto& [r, k] : jac.pattern()) {
    const int col = static_cast<int>(k);
    if (r < c.rhs_out()) {
      out.push_back({kMass, static_cast<int>(c.M_pattern[r].first),
                     static_cast<int>(c.M_pattern[r].second), col});
    } else if (r < c.qdot_out()) {
      out.push_back({kForce, static_cast<int>(r - c.rhs_out()), 0, col});
    } else if (r < c.G_out()) {
      out.push_back({-1, 0, 0, col});  // q̇: not differentiated (never in the pattern)
    } else if (r < c.c_out()) {
      const auto& g = c.G_pattern[r - c.G_out()];
      out.push_back({kConstraintRow, static_cast<int>(g.first), static_cast<int>(g.second), col});
    } else if (r < c.Cdot_out()) {
      out.push_back({kBias, static_cast<int>(r - c.c_out()), 0, col});
    } else if (r < c.C_out()) {
      out.push_back({kRate, static_cast<int>(r - c.Cdot_out()), 0, col});
    } else {
      out.push_back({kValue, static_cast<int>(r - c.C_out()), 0, col});
    }
  }
  return out;
}

// Structural sparsity of the solution: the KKT matrix [M Gᵀ; G 0] couples the rows of each
// connected component of its graph (its inverse is block-diagonal over them, generally full
// within one), so a' has column k non-zero in the velocity rows of every component that column
// k's right-hand side touches. Returns, per column, its non-zero rows (sorted).
std::vector<std::vector<int>> solution_pattern(const DynamicsJacobian& jac,
                                               const std::vector<Entry>& es, size_t columns) {
  const CompiledModel& c = jac.model();
  const size_t n = c.nv, size = c.nv + c.m;
  std::vector<size_t> parent(size);
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  const auto join = [&](size_t a, size_t b) { parent[find(a)] = find(b); };
  for (const auto& [i, j] : c.M_pattern) join(i, j);
  for (const auto& [row, j] : c.G_pattern) join(n + row, j);
  std::vector<std::vector<size_t>> touched(columns);
  for (const Entry& e : es) {
    auto& t = touched[static_cast<size_t>(e.col)];
    switch (e.kind) {
      case kMass:
        t.push_back(find(static_cast<size_t>(e.i)));
        t.push_back(find(static_cast<size_t>(e.j)));
        break;
      case kForce:
        t.push_back(find(static_cast<size_t>(e.i)));
        break;
      case kConstraintRow:
        t.push_back(find(static_cast<size_t>(e.j)));
        t.push_back(find(n + static_cast<size_t>(e.i)));
        break;
      case kBias:
      case kRate:
      case kValue:
        t.push_back(find(n + static_cast<size_t>(e.i)));
        break;
      default:
        break;
    }
  }
  std::vector<std::vector<int>> rows(columns);
  for (size_t k = 0; k < columns; ++k)
    for (size_t i = 0; i < n; ++i)
      if (std::count(touched[k].begin(), touched[k].end(), find(i)))
        rows[k].push_back(static_cast<int>(i));
  return rows;
}

std::string int_array(const std::string& name, const std::vector<int>& x, bool exported) {
  std::string s = fmt::format("{}const int {}[{}] = {{", exported ? "" : "static ", name,
                              std::max<size_t>(x.size(), 1));
  for (size_t i = 0; i < x.size(); ++i) s += fmt::format("{}{}", i ? "," : "", x[i]);
  return s + (x.empty() ? "0};\n" : "};\n");
}

// The CSC arrays of the block of columns [first, first + count) and their size.
struct Block {
  const char* name;
  size_t first, count;
};

const char* kJacobianC = R"C(
int lagrange_jacobian(double t, const double* q, const double* v, const double* u,
                      const double* p, double alpha, double* a_q, double* a_v, double* a_u) {
  const int n = LAGRANGE_N, nk = LAGRANGE_N + LAGRANGE_M, nc = LJ_NCOL;
  /* qdot, a and lambda, in, out, R, M, then Y = M^-1 G^T, G and S = G M^-1 G^T (constraints). */
  double* work = (double*)malloc(sizeof(double) * (LAGRANGE_NQ + nk + LJ_NIN + LJ_NOUT +
                                                   (size_t)nk * nc + (size_t)n * n +
                                                   (size_t)LAGRANGE_M * (2 * n + LAGRANGE_M) + 1));
  double *qdot, *a, *lambda, *in, *out, *R, *M, *Y, *S;
  int i, j, r, k, e, rc;
  if (!work) return 3;
  qdot = work; a = qdot + LAGRANGE_NQ; lambda = a + n; in = lambda + LAGRANGE_M;
  out = in + LJ_NIN; R = out + LJ_NOUT; M = R + (size_t)nk * nc; Y = M + (size_t)n * n;
  S = Y + (size_t)LAGRANGE_M * n;
  rc = lagrange_dynamics(t, q, v, u, p, alpha, qdot, a, lambda);
  if (rc) { free(work); return rc; }
  in[0] = t;
  for (i = 0; i < LAGRANGE_NQ; ++i) in[1 + i] = q[i];
  for (i = 0; i < n; ++i) in[1 + LAGRANGE_NQ + i] = v[i];
  for (i = 0; i < 3 * LAGRANGE_K; ++i) in[1 + LAGRANGE_NQ + n + i] = u[i];
  for (i = 0; i < LAGRANGE_NP; ++i) in[1 + LAGRANGE_NQ + n + 3 * LAGRANGE_K + i] = p[i];
  lagrange_jacobian_tape(in, out);
  /* Right-hand sides [f' - M'a - G'^T lambda; gamma' - G'a], one column per derivative. */
  for (i = 0; i < nk * nc; ++i) R[i] = 0.0;
  for (e = 0; e < LJ_NE; ++e) {
    const double d = out[LJ_NVAL + e];
    double* col = R + (size_t)lj_col[e] * nk;
    switch (lj_kind[e]) {
      case 0: col[lj_i[e]] -= d * a[lj_j[e]]; if (lj_i[e] != lj_j[e]) col[lj_j[e]] -= d * a[lj_i[e]]; break;
      case 1: col[lj_i[e]] += d; break;
      case 2: col[lj_j[e]] -= d * lambda[lj_i[e]]; col[n + lj_i[e]] -= d * a[lj_j[e]]; break;
      case 3: col[n + lj_i[e]] -= d; break;
      case 4: col[n + lj_i[e]] -= 2.0 * alpha * d; break;
      case 5: col[n + lj_i[e]] -= alpha * alpha * d; break;
      default: break;
    }
  }
  for (i = 0; i < n * n; ++i) M[i] = 0.0;
  for (e = 0; e < LJ_NM; ++e) {
    M[lj_M_row[e] * n + lj_M_col[e]] = out[e];
    M[lj_M_col[e] * n + lj_M_row[e]] = out[e];
  }
  if (lg_chol(M, n)) { free(work); return 1; }
#if LAGRANGE_M > 0
  /* Range space, as lagrange_dynamics: Y = M^-1 G^T (rows), S = G Y, lambda' = S^-1 (G x - r2). */
  for (i = 0; i < LAGRANGE_M * n; ++i) Y[i] = 0.0;
  for (e = 0; e < LJ_NG; ++e) Y[lj_G_row[e] * n + lj_G_col[e]] = out[LJ_G_OUT + e];
  for (i = 0; i < LAGRANGE_M * n; ++i) S[i] = Y[i];  /* G, kept in S's space meanwhile */
  for (r = 0; r < LAGRANGE_M; ++r) lg_chol_solve(M, n, Y + r * n);
  {
    double* G = S;
    double* SS = S + (size_t)LAGRANGE_M * n;
    for (r = 0; r < LAGRANGE_M; ++r)
      for (i = 0; i < LAGRANGE_M; ++i) {
        double s = 0.0;
        for (j = 0; j < n; ++j) s += G[r * n + j] * Y[i * n + j];
        SS[r * LAGRANGE_M + i] = s;
      }
    if (lg_chol(SS, LAGRANGE_M)) { free(work); return 2; }
    for (k = 0; k < nc; ++k) {
      double* x = R + (size_t)k * nk;
      double* l = x + n;
      lg_chol_solve(M, n, x);
      for (r = 0; r < LAGRANGE_M; ++r) {
        double s = 0.0;
        for (j = 0; j < n; ++j) s += G[r * n + j] * x[j];
        l[r] = s - l[r];
      }
      lg_chol_solve(SS, LAGRANGE_M, l);
      for (j = 0; j < n; ++j)
        for (r = 0; r < LAGRANGE_M; ++r) x[j] -= Y[r * n + j] * l[r];
    }
  }
#else
  (void)Y; (void)S; (void)r; (void)j;
  for (k = 0; k < nc; ++k) lg_chol_solve(M, n, R + (size_t)k * nk);
#endif
  for (k = 0; k < LAGRANGE_NQ; ++k)
    for (e = lagrange_a_q_colptr[k]; e < lagrange_a_q_colptr[k + 1]; ++e)
      a_q[e] = R[(size_t)k * nk + lagrange_a_q_rowind[e]];
  for (k = 0; k < n; ++k)
    for (e = lagrange_a_v_colptr[k]; e < lagrange_a_v_colptr[k + 1]; ++e)
      a_v[e] = R[(size_t)(LAGRANGE_NQ + k) * nk + lagrange_a_v_rowind[e]];
  for (k = 0; k < LAGRANGE_K; ++k)
    for (e = lagrange_a_u_colptr[k]; e < lagrange_a_u_colptr[k + 1]; ++e)
      a_u[e] = R[(size_t)(LAGRANGE_NQ + n + k) * nk + lagrange_a_u_rowind[e]];
  (void)a_u;
  free(work);
  return 0;
}
)C";

}  // namespace

void export_c_jacobian(const DynamicsJacobian& jac, const std::string& dir) {
  const CompiledModel& cm = jac.model();
  if (jac.input_names() != cm.input_names || !jac.output_names().empty())
    throw std::invalid_argument(
        "export_c_jacobian: expected the derivatives with respect to the model's inputs, in "
        "order, and no outputs");
  export_c(cm, dir);
  const std::vector<Entry> es = entries(jac);
  const size_t columns = cm.nq + cm.nv + cm.k;
  const std::vector<std::vector<int>> rows = solution_pattern(jac, es, columns);
  const Block blocks[3] = {{"a_q", 0, cm.nq}, {"a_v", cm.nq, cm.nv}, {"a_u", cm.nq + cm.nv, cm.k}};

  std::string header =
      "/* Generated by lagrange: exact derivatives of lagrange_dynamics (lagrange_model.h). C99.\n"
      "   Compressed sparse column (CSC) patterns: the entries of column j are rows\n"
      "   <name>_rowind[<name>_colptr[j]] ... [<name>_colptr[j + 1] - 1], values in that order. "
      "*/\n"
      "#ifndef LAGRANGE_JACOBIAN_H\n#define LAGRANGE_JACOBIAN_H\n\n#include "
      "\"lagrange_model.h\"\n\n";
  std::string arrays;
  for (const Block& b : blocks) {
    std::vector<int> colptr{0}, rowind;
    for (size_t k = b.first; k < b.first + b.count; ++k) {
      rowind.insert(rowind.end(), rows[k].begin(), rows[k].end());
      colptr.push_back(static_cast<int>(rowind.size()));
    }
    std::string upper = b.name;
    std::transform(upper.begin(), upper.end(), upper.begin(), ::toupper);
    header += fmt::format("#define LAGRANGE_{}_NNZ {}\n", upper, rowind.size());
    header += fmt::format(
        "extern const int lagrange_{0}_colptr[];\nextern const int lagrange_{0}_rowind[];\n",
        b.name);
    arrays += int_array(fmt::format("lagrange_{}_colptr", b.name), colptr, true);
    arrays += int_array(fmt::format("lagrange_{}_rowind", b.name), rowind, true);
  }
  header += fmt::format(
      "\n/* da/dq (LAGRANGE_N x LAGRANGE_NQ), da/dv (LAGRANGE_N x LAGRANGE_N) and da/du\n"
      "   (LAGRANGE_N x LAGRANGE_K, columns the inputs {}, their rates held) at the arguments of\n"
      "   lagrange_dynamics, into arrays of LAGRANGE_A_Q_NNZ, LAGRANGE_A_V_NNZ and\n"
      "   LAGRANGE_A_U_NNZ values in the patterns' order. Returns 0, or lagrange_dynamics' code,\n"
      "   or 3 when memory runs out. */\n"
      "int lagrange_jacobian(double t, const double* q, const double* v, const double* u,\n"
      "                      const double* p, double alpha, double* a_q, double* a_v, double* "
      "a_u);\n\n"
      "#endif\n",
      c_name_list(cm.input_names));

  std::string source =
      "/* Generated by lagrange. Compile with -ffp-contract=off to match the engine bit for bit. "
      "*/\n"
      "#include <math.h>\n#include <stdlib.h>\n#include \"lagrange_jacobian.h\"\n\n";
  source += fmt::format(
      "#define LJ_NIN {}\n#define LJ_NOUT {}\n#define LJ_NVAL {}\n#define LJ_NE {}\n#define "
      "LJ_NCOL "
      "{}\n#define LJ_NM {}\n#define LJ_NG {}\n#define LJ_G_OUT {}\n\n",
      cm.input_count(), std::max<size_t>(jac.tape().num_outputs(), 1), jac.value_count(), es.size(),
      columns, cm.M_pattern.size(), cm.G_pattern.size(), cm.G_out());
  source += arrays;
  std::vector<int> kind, ei, ej, ecol, mr, mc, gr, gc;
  for (const Entry& e : es) {
    kind.push_back(e.kind);
    ei.push_back(e.i);
    ej.push_back(e.j);
    ecol.push_back(e.col);
  }
  for (const auto& [i, j] : cm.M_pattern)
    mr.push_back(static_cast<int>(i)), mc.push_back(static_cast<int>(j));
  for (const auto& [i, j] : cm.G_pattern)
    gr.push_back(static_cast<int>(i)), gc.push_back(static_cast<int>(j));
  source += int_array("lj_kind", kind, false) + int_array("lj_i", ei, false) +
            int_array("lj_j", ej, false) + int_array("lj_col", ecol, false) +
            int_array("lj_M_row", mr, false) + int_array("lj_M_col", mc, false);
  if (cm.m > 0) source += int_array("lj_G_row", gr, false) + int_array("lj_G_col", gc, false);
  source += "\n" + jac.tape().to_c("lagrange_jacobian_tape", true) + "\n";
  source += c_cholesky_source();
  source += kJacobianC;
  write_file_atomically(dir + "/lagrange_jacobian.h", header);
  write_file_atomically(dir + "/lagrange_jacobian.c", source);
}

}  // namespace lagrange
