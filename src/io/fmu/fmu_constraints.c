/* Part of the FMU that `lagrange export --fmu` writes (docs/fmu.md): keeping the state on its
   manifold. Included by lagrange_fmu.c after lagrange_model.c and lagrange_fmu_model.h. */

#if LAGRANGE_M > 0
/* Largest |x_i|. */
static double lg_max_abs(const double* x, int n) {
  double m = 0.0;
  int i;
  for (i = 0; i < n; ++i) {
    const double a = fabs(x[i]);
    if (!(a <= m)) m = a; /* NaN wins */
  }
  return m;
}

/* The dynamics tape at (t, y = (q, v)) with the instance's inputs and parameters into
   c->tape_out. */
static void lg_eval_tape(Instance* c, double t, const double* y) {
  lg_pack_inputs(c, t, y);
  lagrange_tape(c->tape_in, c->tape_out);
}

/* Minimum-norm solution dx (n entries) of J dx = r for the m x n matrix J (row-major) through
   the Cholesky factor of J J^T; r is overwritten. 1 when J J^T is singular. */
static int lg_min_norm(Instance* c, const double* J, int n, double* r, double* dx) {
  double* S = c->proj_S;
  int a, b, j;
  for (a = 0; a < LAGRANGE_M; ++a)
    for (b = 0; b < LAGRANGE_M; ++b) {
      double s = 0.0;
      for (j = 0; j < n; ++j) s += J[a * n + j] * J[b * n + j];
      S[a * LAGRANGE_M + b] = s;
    }
  if (lg_chol(S, LAGRANGE_M)) return 1;
  lg_chol_solve(S, LAGRANGE_M, r);
  for (j = 0; j < n; ++j) {
    double s = 0.0;
    for (a = 0; a < LAGRANGE_M; ++a) s += J[a * n + j] * r[a];
    dx[j] = s;
  }
  return 0;
}

/* docs/theory.md §4.3 (projection): damped Gauss-Newton onto C(q, t) = 0 with the least-squares
   change of the coordinates not in `fixed`, then the least-squares change of v that gives
   Cdot = 0, of y = (q, v) in place. 0 when max |C| reaches tol; 1 when it does not (in 50
   iterations, or for want of descent: q is then the best found, v still projected); 2 when
   singular. */
static int lg_project(Instance* c, double t, double* y, const int* fixed, double tol) {
  double* q = y;
  double* v = y + LAGRANGE_NQ;
  const double* out = c->tape_out;
  double* J = c->proj_J;
  double* r = c->proj_r;
  double* d = c->proj_d;
  int it, e, i, halvings, status = 0;
  lg_eval_tape(c, t, y);
  for (it = 0;; ++it) {
    double here, there, scale = 1.0;
    if (lg_max_abs(out + LG_OUT_C, LAGRANGE_M) <= tol) break;
    if (it == 50) {
      status = 1;
      break;
    }
    for (i = 0; i < LAGRANGE_M * LAGRANGE_NQ; ++i) J[i] = 0.0;
    for (e = 0; e < LG_NCQ; ++e)
      if (!fixed[lg_Cq_col[e]]) J[lg_Cq_row[e] * LAGRANGE_NQ + lg_Cq_col[e]] = out[LG_OUT_CQ + e];
    for (i = 0; i < LAGRANGE_M; ++i) r[i] = -out[LG_OUT_C + i];
    here = lg_max_abs(out + LG_OUT_C, LAGRANGE_M);
    if (lg_min_norm(c, J, LAGRANGE_NQ, r, d)) return 2;
    for (i = 0; i < LAGRANGE_NQ; ++i) c->proj_q[i] = q[i];
    for (halvings = 0; halvings <= 30; ++halvings, scale *= 0.5) {
      for (i = 0; i < LAGRANGE_NQ; ++i) q[i] = c->proj_q[i] + scale * d[i];
      lg_eval_tape(c, t, y);
      there = lg_max_abs(out + LG_OUT_C, LAGRANGE_M);
      if (there < here) break; /* false for NaN: a step into a pole is halved */
    }
    if (halvings > 30) { /* no descent along the Gauss-Newton direction */
      for (i = 0; i < LAGRANGE_NQ; ++i) q[i] = c->proj_q[i];
      lg_eval_tape(c, t, y);
      status = 1;
      break;
    }
  }
  /* G v = -(Cdot - G v): the velocity change is the minimum-norm solution of G dv = -Cdot. */
  for (i = 0; i < LAGRANGE_M * LAGRANGE_N; ++i) J[i] = 0.0;
  for (e = 0; e < LAGRANGE_NG; ++e)
    if (!(G_col[e] < LG_PLAIN && fixed[G_col[e]]))
      J[G_row[e] * LAGRANGE_N + G_col[e]] = out[LG_OUT_G + e];
  for (i = 0; i < LAGRANGE_M; ++i) r[i] = -out[LG_OUT_CDOT + i];
  if (lg_min_norm(c, J, LAGRANGE_N, r, d)) return 2;
  for (i = 0; i < LAGRANGE_N; ++i) v[i] += d[i];
  return status;
}
#endif

#if LG_NROT > 0
/* docs/theory.md §4.4: each free body's R replaced by its nearest rotation (the polar factor,
   by Newton's iteration R <- (R + R^-T) / 2) where ||R^T R - 1||_F exceeds tol; 1 when some R
   is singular. */
static int lg_orthonormalize(double* q, double tol) {
  int b, it, i, j, k;
  for (b = 0; b < LG_NROT; ++b) {
    double* R = q + lg_rotations[b];
    for (it = 0; it < 20; ++it) {
      double drift = 0.0, det, cof[9];
      for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) {
          double s = i == j ? -1.0 : 0.0;
          for (k = 0; k < 3; ++k) s += R[3 * k + i] * R[3 * k + j];
          drift += s * s;
        }
      if (sqrt(drift) <= tol) break;
      /* cof = cofactor matrix of R, so R^-T = cof / det R. */
      cof[0] = R[4] * R[8] - R[5] * R[7];
      cof[1] = R[5] * R[6] - R[3] * R[8];
      cof[2] = R[3] * R[7] - R[4] * R[6];
      cof[3] = R[2] * R[7] - R[1] * R[8];
      cof[4] = R[0] * R[8] - R[2] * R[6];
      cof[5] = R[1] * R[6] - R[0] * R[7];
      cof[6] = R[1] * R[5] - R[2] * R[4];
      cof[7] = R[2] * R[3] - R[0] * R[5];
      cof[8] = R[0] * R[4] - R[1] * R[3];
      det = R[0] * cof[0] + R[1] * cof[1] + R[2] * cof[2];
      if (!(fabs(det) > 1e-300)) return 1;
      for (i = 0; i < 9; ++i) R[i] = 0.5 * (R[i] + cof[i] / det);
    }
  }
  return 0;
}
#endif

/* After an accepted step of fmi2DoStep (docs/theory.md §4.3, "Projecting when the drift
   matters"), as `lagrange simulate` does after internal steps: the constraints projected when
   max |C| or max |Cdot| exceeds max(1e-11, atol), each R made orthonormal past 1e-11; the
   derivative at the new state re-evaluated when something moved. 0, or -1 with a message. */
static int lg_after_step(Instance* c) {
  int moved = 0;
#if LG_NROT > 0
  if (c->project) {
    double before[LAGRANGE_NQ];
    int i;
    for (i = 0; i < LAGRANGE_NQ; ++i) before[i] = c->y[i];
    if (lg_orthonormalize(c->y, 1e-11)) {
      lg_log_error(c, "fmi2DoStep: a rotation matrix became singular at t = %.17g", c->t);
      return -1;
    }
    for (i = 0; i < LAGRANGE_NQ; ++i) moved |= before[i] != c->y[i];
  }
#endif
#if LAGRANGE_M > 0
  if (c->project) {
    const double allowed = c->atol > 1e-11 ? c->atol : 1e-11;
    lg_eval_tape(c, c->t, c->y);
    if (lg_max_abs(c->tape_out + LG_OUT_C, LAGRANGE_M) > allowed ||
        lg_max_abs(c->tape_out + LG_OUT_CDOT, LAGRANGE_M) > allowed) {
      if (lg_project(c, c->t, c->y, lg_none_fixed, 1e-13) == 2) {
        lg_log_error(c, "fmi2DoStep: the constraints are singular at t = %.17g", c->t);
        return -1;
      }
      moved = 1;
    }
  }
#endif
  if (moved && lg_rhs(c, c->t, c->y, c->k[0]) != LG_RHS_OK) {
    lg_log_error(c, "fmi2DoStep: the dynamics cannot be evaluated at t = %.17g", c->t);
    return -1;
  }
  return 0;
}
