/* Part of the FMU that `lagrange export --fmu` writes (docs/fmu.md): the Co-Simulation integrator.
   Dormand-Prince 5(4) (Hairer, Norsett, Wanner, Solving ODEs I, Table II.5.2), first same as last,
   error per component scaled by atol + rtol max(|y|, |y_new|), step factor 0.9 err^(-1/5) kept in
   [0.2, 10]. Included by lagrange_fmu.c; needs lg_rhs (the model's y' = f(t, y)) and
   lg_after_step (the drift correction), both defined there before this file. */

static const double lg_c[7] = {0.0, 1.0 / 5, 3.0 / 10, 4.0 / 5, 8.0 / 9, 1.0, 1.0};
static const double lg_a[7][6] = {
    {0, 0, 0, 0, 0, 0},
    {1.0 / 5, 0, 0, 0, 0, 0},
    {3.0 / 40, 9.0 / 40, 0, 0, 0, 0},
    {44.0 / 45, -56.0 / 15, 32.0 / 9, 0, 0, 0},
    {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729, 0, 0},
    {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656, 0},
    {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84}};
/* b - b_hat: the embedded fourth-order solution's difference from the fifth-order one. */
static const double lg_e[7] = {71.0 / 57600,      0.0,         -71.0 / 16695, 71.0 / 1920,
                               -17253.0 / 339200, 22.0 / 525, -1.0 / 40};

/* Largest number of internal steps one fmi2DoStep may take before it fails. */
#define LG_MAX_STEPS 10000000L

/* Weighted RMS norm of x with the scale atol + rtol max(|y|, |z|). */
static double lg_wrms(const Instance* c, const double* x, const double* y, const double* z) {
  double s = 0.0;
  int i;
  for (i = 0; i < LG_NX; ++i) {
    const double ay = fabs(y[i]), az = fabs(z[i]);
    const double sc = c->atol + c->rtol * (ay > az ? ay : az);
    s += (x[i] / sc) * (x[i] / sc);
  }
  return sqrt(s / LG_NX);
}

/* A first step from ||y|| / ||f|| (Hairer's starting-step rule, its first part), at most h_max. */
static double lg_first_step(const Instance* c, double h_max) {
  const double d0 = lg_wrms(c, c->y, c->y, c->y), d1 = lg_wrms(c, c->k[0], c->y, c->y);
  double h = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
  return h < h_max ? h : h_max;
}

/* Advance c->y from c->t to t_end; 0, or -1 with a message logged when a step fails. */
static int lg_integrate(Instance* c, double t_end) {
  long steps = 0;
  int i, s, j, rc = 0;
  if (lg_rhs(c, c->t, c->y, c->k[0]) != LG_RHS_OK) {
    lg_log_error(c, "fmi2DoStep: the dynamics cannot be evaluated at t = %.17g", c->t);
    return -1;
  }
  if (!(c->h > 0.0)) c->h = lg_first_step(c, t_end - c->t);
  while (c->t < t_end) {
    double h = c->h, t_new, err;
    int last = 0;
    if (c->t + h >= t_end) {
      h = t_end - c->t;
      last = 1;
    }
    if (++steps > LG_MAX_STEPS || !(h > 1e-14 * fabs(c->t)) || !(h > 0.0)) {
      lg_log_error(c, "fmi2DoStep: at t = %.17g the step size fell to %.3g (%ld steps)", c->t, h,
                   steps);
      return -1;
    }
    for (s = 1; s < 7 && rc == LG_RHS_OK; ++s) {
      for (i = 0; i < LG_NX; ++i) {
        double d = 0.0;
        for (j = 0; j < s; ++j) d += lg_a[s][j] * c->k[j][i];
        c->y_stage[i] = c->y[i] + h * d;
      }
      rc = lg_rhs(c, c->t + lg_c[s] * h, c->y_stage, c->k[s]);
    }
    if (rc == LG_RHS_SINGULAR) {
      lg_log_error(c, "fmi2DoStep: the mass matrix or the constraints are singular near t = %.17g",
                   c->t);
      return -1;
    }
    /* The seventh stage is at the fifth-order solution (y_stage), first same as last. */
    for (i = 0; i < LG_NX; ++i) {
      double d = 0.0;
      for (j = 0; j < 7; ++j) d += lg_e[j] * c->k[j][i];
      c->y_error[i] = h * d;
    }
    /* A stage that is not finite rejects the step (it is retried shorter). */
    err = rc == LG_RHS_OK ? lg_wrms(c, c->y_error, c->y, c->y_stage) : HUGE_VAL;
    rc = LG_RHS_OK;
    if (err <= 1.0) {
      const double grow = err > 0.0 ? 0.9 * pow(err, -0.2) : 10.0;
      t_new = last ? t_end : c->t + h;
      for (i = 0; i < LG_NX; ++i) {
        c->y[i] = c->y_stage[i];
        c->k[0][i] = c->k[6][i];
      }
      c->t = t_new;
      /* A step shortened to land on t_end does not shrink the next one. */
      if (!last || h * (grow < 10.0 ? grow : 10.0) > c->h) c->h = h * (grow < 10.0 ? grow : 10.0);
      if (lg_after_step(c)) return -1;
    } else {
      const double shrink = err == err ? 0.9 * pow(err, -0.2) : 0.0;
      c->h = h * (shrink > 0.2 ? shrink : 0.2);
    }
  }
  return 0;
}
