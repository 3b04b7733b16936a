/* Part of the FMU that `lagrange export --fmu` writes (docs/fmu.md): the Co-Simulation
   integrator, DOP853 as `lagrange simulate` runs it (src/integrate/dop853.cpp; Hairer, Norsett,
   Wanner, Solving ODEs I, §II.10): Dormand and Prince's 8(5,3) pair with the coefficients of
   lagrange_fmu_model.h (written from the engine's own table), the error
   err = |h| ||e5||^2 / sqrt(||e5||^2 + 0.01 ||e3||^2) in the RMS norm scaled by
   atol + rtol max(|y0|, |y1|), and Hairer's PI step control
   h_new = h clamp(0.9 err^-(1/8 - 0.2 beta) err_prev^beta, 1/3, 6), beta = 0.04, no growth right
   after a rejection. Included by lagrange_fmu.c; needs lg_rhs, lg_after_step and lg_check_stop. */

#define LG_STAGES 12 /* stage 13, f(t + h, y1), is the next step's first */
#define LG_BETA 0.04
#define LG_SAFETY 0.9
#define LG_SMALLEST_FACTOR 0.333
#define LG_LARGEST_FACTOR 6.0

/* Root mean square of x_i / (atol + rtol |y_i|). */
static double lg_rms(const Instance* c, const double* x, const double* y) {
  double s = 0.0;
  int i;
  for (i = 0; i < LG_NX; ++i) {
    const double w = c->atol + c->rtol * fabs(y[i]);
    s += (x[i] / w) * (x[i] / w);
  }
  return sqrt(s / LG_NX);
}

/* Hairer's starting step (as Dop853::initial_step): from ||y|| / ||f|| and one more evaluation
   estimating the second derivative, at most `span`. 0 when that evaluation fails. */
static double lg_initial_step(Instance* c, double span) {
  const double d0 = lg_rms(c, c->y, c->y), d1 = lg_rms(c, c->k[0], c->y);
  double h = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1, d2, d12, h1;
  int i;
  if (h > span) h = span;
  for (i = 0; i < LG_NX; ++i) c->y_stage[i] = c->y[i] + h * c->k[0][i];
  if (lg_rhs(c, c->t + h, c->y_stage, c->k[1]) != LG_RHS_OK) return 0.0;
  for (i = 0; i < LG_NX; ++i) c->y_stage[i] = c->k[1][i] - c->k[0][i];
  d2 = lg_rms(c, c->y_stage, c->y) / h;
  d12 = d2 > d1 ? d2 : d1;
  h1 = d12 <= 1e-15 ? (h * 1e-3 > 1e-6 ? h * 1e-3 : 1e-6) : pow(0.01 / d12, 0.125);
  h = 100.0 * h < h1 ? 100.0 * h : h1;
  return h < span ? h : span;
}

/* Stages 2-12 at step h and the eighth-order solution in c->y_new; LG_RHS_OK or the first
   failure of lg_rhs. */
static int lg_stages(Instance* c, double h) {
  int s, j, i, rc;
  for (s = 1; s < LG_STAGES; ++s) {
    for (i = 0; i < LG_NX; ++i) {
      double d = 0.0;
      for (j = 0; j < s; ++j) d += lg_dop_a[s][j] * c->k[j][i];
      c->y_stage[i] = c->y[i] + h * d;
    }
    rc = lg_rhs(c, c->t + lg_dop_c[s] * h, c->y_stage, c->k[s]);
    if (rc != LG_RHS_OK) return rc;
  }
  for (i = 0; i < LG_NX; ++i) {
    double d = 0.0;
    for (j = 0; j < LG_STAGES; ++j) d += lg_dop_b[j] * c->k[j][i];
    c->y_new[i] = c->y[i] + h * d;
  }
  return LG_RHS_OK;
}

/* The error of the step just taken (docs/theory.md §8, DOP853). */
static double lg_error(const Instance* c, double h) {
  double sum5 = 0.0, sum3 = 0.0, den;
  int i, j;
  for (i = 0; i < LG_NX; ++i) {
    double e5 = 0.0, e3 = 0.0;
    const double a = fabs(c->y[i]), b = fabs(c->y_new[i]);
    const double w = c->atol + c->rtol * (a > b ? a : b);
    for (j = 0; j < LG_STAGES; ++j) {
      e5 += lg_dop_e5[j] * c->k[j][i];
      e3 += lg_dop_e3[j] * c->k[j][i];
    }
    sum5 += (e5 / w) * (e5 / w);
    sum3 += (e3 / w) * (e3 / w);
  }
  den = sum5 + 0.01 * sum3;
  if (den <= 0.0) den = 1.0;
  return fabs(h) * sum5 / sqrt(LG_NX * den);
}

/* Largest number of internal steps one fmi2DoStep may take before it fails. */
#define LG_MAX_STEPS 10000000L

/* Advance c->y from c->t to t_end; 0, or -1 with a message logged when a step fails, or 1 when a
   stop_when condition became true (fmu_events.c: the instance is then at its crossing). A stage
   that is not finite rejects the step, which is retried shorter. */
static int lg_integrate(Instance* c, double t_end) {
  long steps = 0;
  int i;
  if (lg_rhs(c, c->t, c->y, c->k[0]) != LG_RHS_OK) {
    lg_log_error(c, "fmi2DoStep: the dynamics cannot be evaluated at t = %.17g", c->t);
    return -1;
  }
  if (!(c->h > 0.0)) {
    c->h = lg_initial_step(c, t_end - c->t);
    c->err_prev = 1e-4;
    c->rejections = 0;
  }
  while (c->t < t_end) {
    double h = c->h;
    for (;;) {
      const int last = c->t + 1.01 * h >= t_end;
      const double wanted = h; /* the step a shortened last one replaces, kept for the next */
      double err, grow;
      int rc;
      if (last) h = t_end - c->t;
      if (++steps > LG_MAX_STEPS || !(h > 16.0 * 2.220446049250313e-16 * fabs(c->t)) ||
          !(h > 0.0)) {
        lg_log_error(c, "fmi2DoStep: at t = %.17g the step size fell to %.3g (%ld steps)", c->t, h,
                     steps);
        return -1;
      }
      rc = lg_stages(c, h);
      if (rc == LG_RHS_SINGULAR) {
        lg_log_error(c,
                     "fmi2DoStep: the mass matrix or the constraints are singular near t = "
                     "%.17g",
                     c->t);
        return -1;
      }
      err = rc == LG_RHS_OK ? lg_error(c, h) : HUGE_VAL;
      if (!(err == err)) err = HUGE_VAL;
      grow = pow(err, 0.125 - 0.2 * LG_BETA); /* err ~ h^8 */
      if (err <= 1.0) {
        double shrink = grow / pow(c->err_prev, LG_BETA) / LG_SAFETY, h_next;
        if (shrink < 1.0 / LG_LARGEST_FACTOR) shrink = 1.0 / LG_LARGEST_FACTOR;
        if (shrink > 1.0 / LG_SMALLEST_FACTOR) shrink = 1.0 / LG_SMALLEST_FACTOR;
        h_next = h / shrink;
        if (c->rejections > 0 && h_next > h) h_next = h;
        c->err_prev = err > 1e-4 ? err : 1e-4;
#if LG_NZ > 0
        if (!c->locating) { /* where a crossing is located from */
          c->t_prev = c->t;
          for (i = 0; i < LG_NX; ++i) c->y_prev[i] = c->y[i];
        }
#endif
        for (i = 0; i < LG_NX; ++i) c->y[i] = c->y_new[i];
        c->t = last ? t_end : c->t + h;
        c->h = last && wanted > h_next ? wanted : h_next;
        c->rejections = 0;
        if (lg_rhs(c, c->t, c->y, c->k[0]) != LG_RHS_OK) {
          lg_log_error(c, "fmi2DoStep: the dynamics cannot be evaluated at t = %.17g", c->t);
          return -1;
        }
        if (lg_after_step(c)) return -1;
#if LG_NZ > 0
        if (!c->locating) {
          const int stop = lg_check_stop(c);
          if (stop) return stop;
        }
#endif
        break;
      }
      ++c->rejections;
      h /= (grow / LG_SAFETY < 1.0 / LG_SMALLEST_FACTOR ? grow / LG_SAFETY
                                                        : 1.0 / LG_SMALLEST_FACTOR);
    }
  }
  return 0;
}
