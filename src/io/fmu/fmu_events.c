/* Part of the FMU that `lagrange export --fmu` writes (docs/fmu.md, "Stop conditions"): the
   model's stop_when conditions, g_i = rhs - lhs of `lhs < rhs` (lhs - rhs of `lhs > rhs`),
   positive exactly when condition i holds (docs/model-language.md, "Stop conditions"). They are
   Model Exchange's event indicators; Co-Simulation checks them after every internal step and ends
   fmi2DoStep where one became true. Included by lagrange_fmu.c after fmu_constraints.c (for the
   constraint residual columns) and before fmu_dop853.c. */

#if LG_NZ > 0
/* The trajectory row `lagrange simulate` writes at (t, y) (src/simulation/row_writer.cpp: t, q,
   v, kinetic, potential, energy, outputs, then for constrained models the multipliers, max |C|,
   max |Cdot| and the reactions, then the loads), followed by the parameters: the input of
   lagrange_stop_conditions, into c->row. 0, or the lg_rhs failure when the row needs the
   accelerations or multipliers and the dynamics cannot give them. */
static int lg_stop_row(Instance* c, double t, const double* y) {
  double* row = c->row;
  int i, n = 0;
  row[n++] = t;
  for (i = 0; i < LG_NX; ++i) row[n++] = y[i];
  lg_pack_inputs(c, t, y);
  lagrange_observables(c->tape_in, c->obs);
  row[n++] = c->obs[0];
  row[n++] = c->obs[1];
  row[n++] = c->obs[0] + c->obs[1];
  for (i = 2; i < LG_NOBS - 1; ++i) row[n++] = c->obs[i]; /* the model's outputs */
#if LAGRANGE_M > 0 || LG_NLOADS > 0
  {
    const int rc = lg_rhs(c, t, y, c->dy);
    if (rc != LG_RHS_OK) return rc;
  }
#endif
#if LAGRANGE_M > 0
  for (i = 0; i < LAGRANGE_M; ++i) row[n++] = c->lambda[i];
  lg_eval_tape(c, t, y);
  row[n++] = lg_max_abs(c->tape_out + LG_OUT_C, LAGRANGE_M);
  row[n++] = lg_max_abs(c->tape_out + LG_OUT_CDOT, LAGRANGE_M);
#if LG_NREACTIONS > 0
  for (i = 0; i < LG_NREACTIONS; ++i) /* lambda of the reaction's constraint times its scale */
    row[n++] = c->lambda[lg_reaction_lambda[i]] * c->obs[LG_NOBS - 1 + i];
#endif
#endif
#if LG_NLOADS > 0
  lg_loads(c->obs, c->dy + LAGRANGE_NQ, c->lambda, row + n);
  n += LG_NLOADS;
#endif
  for (i = 0; i < LAGRANGE_NP; ++i) row[n++] = c->p[i];
  return LG_RHS_OK;
}

/* g at (t, y) into `g`; 0, or -1 with a message logged (by `fn`) when the row cannot be made. */
static int lg_stop_values(Instance* c, double t, const double* y, double* g, const char* fn) {
  if (lg_stop_row(c, t, y) != LG_RHS_OK) {
    lg_log_error(c,
                 "%s: the stop conditions cannot be evaluated at t = %.17g (singular mass "
                 "matrix or constraints, or values not finite)",
                 fn, t);
    return -1;
  }
  lagrange_stop_conditions(c->row, g);
  return 0;
}

/* A condition fires when it becomes true: not positive before, positive now (NaN never fires). */
static int lg_fired(double before, double now) {
  return before <= 0.0 && now > 0.0;
}

/* The state at t in (c->t_prev, ...] integrated from the previous internal step's state, as
   `lagrange simulate` re-integrates from its previous sample with DOP853 at the run's tolerances;
   into c->y, c->t. 0 or -1 (logged). */
static int lg_integrate(Instance* c, double t_end);
static int lg_advance_from_prev(Instance* c, double t) {
  int i, rc;
  c->t = c->t_prev;
  for (i = 0; i < LG_NX; ++i) c->y[i] = c->y_prev[i];
  if (!(t - c->t_prev > 32.0 * 2.220446049250313e-16 * (1.0 + fabs(t)))) return 0;
  c->h = 0.0; /* a fresh start, as simulate's refinement integrates with step 0 */
  c->locating = 1;
  rc = lg_integrate(c, t);
  c->locating = 0;
  return rc;
}

/* After an accepted internal step from (c->t_prev, c->y_prev) to (c->t, c->y): 0 when no
   condition fired (c->g_prev updated), -1 on a failure (logged), 1 when one did. Then the
   earliest crossing is located as `lagrange simulate` locates it (src/simulation/simulate.cpp,
   StopWatch; docs/model-language.md, "Stop conditions"): the Illinois variant of regula falsi on
   g_i until the bracket is below 1e-12 (1 + |t|), each trial state integrated from the previous
   step's; the instance is left at the first time g_i > 0 was found, with c->stop_which set. */
static int lg_check_stop(Instance* c) {
  double t_end = c->t, when = HUGE_VAL;
  int i, j, which = -1;
  if (lg_stop_values(c, c->t, c->y, c->g, "fmi2DoStep")) return -1;
  for (i = 0; i < LG_NZ; ++i)
    if (lg_fired(c->g_prev[i], c->g[i])) break;
  if (i == LG_NZ) {
    for (i = 0; i < LG_NZ; ++i) c->g_prev[i] = c->g[i];
    return 0;
  }
  for (j = 0; j < LG_NX; ++j) c->y_end[j] = c->y[j];
  for (j = 0; j < LG_NZ; ++j) c->g_end[j] = c->g[j];
  for (i = 0; i < LG_NZ; ++i) {
    double a = c->t_prev, ga = c->g_prev[i], b = t_end, gb = c->g_end[i];
    int it, side = 0;
    if (!lg_fired(ga, gb)) continue;
    for (j = 0; j < LG_NX; ++j) c->y_try[j] = c->y_end[j];
    for (it = 0; it < 100 && b - a > 1e-12 * (1.0 + fabs(b)); ++it) {
      double x = ga == gb ? 0.5 * (a + b) : b - gb * (b - a) / (gb - ga);
      if (!(x > a && x < b)) x = 0.5 * (a + b);
      if (lg_advance_from_prev(c, x) || lg_stop_values(c, x, c->y, c->g, "fmi2DoStep")) return -1;
      if (c->g[i] > 0.0) {
        b = x, gb = c->g[i];
        for (j = 0; j < LG_NX; ++j) c->y_try[j] = c->y[j];
        if (side == 1) ga /= 2.0;
        side = 1;
      } else {
        a = x, ga = c->g[i];
        if (side == -1) gb /= 2.0;
        side = -1;
      }
    }
    if (b < when) {
      when = b, which = i;
      for (j = 0; j < LG_NX; ++j) c->y_stop[j] = c->y_try[j];
    }
  }
  c->t = when;
  for (j = 0; j < LG_NX; ++j) c->y[j] = c->y_stop[j];
  c->h = 0.0;
  c->stop_which = which;
  return 1;
}
#endif
