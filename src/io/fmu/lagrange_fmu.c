/* FMI 2.0 Model Exchange and Co-Simulation interface of a model exported by
   `lagrange export --fmu` (docs/fmu.md). One translation unit: the model's dynamics
   (lagrange_model.c, as `export --c` writes it), its FMU description (lagrange_fmu_model.h:
   sizes, start values, value references, the observables tape), then the integrator and the
   drift correction. Build: cc -std=c99 -O2 -ffp-contract=off -fPIC -shared lagrange_fmu.c -lm */

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "fmi2Functions.h"
#include "lagrange_fmu_model.h"
#include "lagrange_model.c"

#define LG_MAX1(n) ((n) > 0 ? (n) : 1)
#define LG_NIN (1 + LAGRANGE_NQ + LAGRANGE_N + 3 * LAGRANGE_K + LAGRANGE_NP)

/* Where an instance is in the FMI 2.0 state machine (FMI 2.0 §4.2.4 and §3.2.3). */
enum {
  LG_INSTANTIATED,
  LG_INITIALIZATION,
  LG_EVENT,
  LG_CONTINUOUS,
  LG_STEPPING,
  LG_TERMINATED,
  LG_FAILED
};

typedef struct {
  /* The importer's callbacks and names (copied: fmi2CallbackFunctions has const members). */
  fmi2CallbackLogger logger;
  fmi2CallbackAllocateMemory allocate;
  fmi2CallbackFreeMemory release;
  fmi2ComponentEnvironment env;
  char name[128];
  fmi2Type type;
  int logging, phase;
  /* Everything below is the FMU state (fmi2GetFMUstate copies it). */
  double t;
  double y[LG_NX]; /* q, then v */
  double p[LG_MAX1(LAGRANGE_NP)];
  double held[LG_MAX1(LAGRANGE_K)]; /* external inputs set by the importer */
  int is_held[LG_MAX1(LAGRANGE_K)];
  double alpha, rtol, atol;
  int project;
  double h;        /* the integrator's next step */
  double err_prev; /* its last accepted error (the PI control's memory) */
  int rejections;  /* rejected tries of the current step */
  /* stop_when (fmu_events.c): g at the last accepted step or event, the condition that stopped
     the run (-1: none) and whether it did. */
  double g_prev[LG_MAX1(LG_NZ)];
  int stop_which, stopped;
  /* Scratch. */
  double dy[LG_NX], lambda[LG_MAX1(LAGRANGE_M)], obs[LG_MAX1(LG_NOBS_ALL)];
  double k[12][LG_NX], y_stage[LG_NX], y_new[LG_NX];
  double tape_in[LG_NIN], tape_out[LAGRANGE_NOUT];
#if LG_NZ > 0
  double g[LG_NZ], g_end[LG_NZ], row[LG_NROW + LAGRANGE_NP], t_prev;
  double y_prev[LG_NX], y_end[LG_NX], y_try[LG_NX], y_stop[LG_NX];
  int locating; /* lg_integrate is re-integrating to locate a crossing: no checks */
#endif
#if LAGRANGE_M > 0
  double proj_J[LAGRANGE_M * (LAGRANGE_NQ > LAGRANGE_N ? LAGRANGE_NQ : LAGRANGE_N)];
  double proj_S[LAGRANGE_M * LAGRANGE_M], proj_r[LAGRANGE_M];
  double proj_d[LAGRANGE_NQ > LAGRANGE_N ? LAGRANGE_NQ : LAGRANGE_N], proj_q[LAGRANGE_NQ];
#endif
} Instance;

/* Message to the importer's logger when it has one; "%s" keeps the text from being a format. */
static void lg_log(Instance* c, fmi2Status status, const char* category, const char* format,
                   va_list args) {
  char message[512];
  if (!c->logger) return;
  vsnprintf(message, sizeof message, format, args);
  c->logger(c->env, c->name, status, category, "%s", message);
}

/* An error: logged (whatever the logging setting) and the instance unusable until fmi2Reset. */
static void lg_log_error(Instance* c, const char* format, ...) {
  va_list args;
  va_start(args, format);
  lg_log(c, fmi2Error, "logStatusError", format, args);
  va_end(args);
  c->phase = LG_FAILED;
}

/* A message of category logEvents (a stop_when condition that fired), when logging is on. */
static void lg_log_event(Instance* c, const char* format, ...) {
  va_list args;
  if (!c->logging) return;
  va_start(args, format);
  lg_log(c, fmi2OK, "logEvents", format, args);
  va_end(args);
}

/* The inputs u, u_dot, u_ddot (3 K values) at t: the model's definitions, with each external
   input the importer set held at its value with zero rates (Dynamics::hold_input). */
static void lg_current_inputs(Instance* c, double t, double* u) {
  int i;
  lagrange_inputs(t, c->p, u);
  for (i = 0; i < LAGRANGE_K; ++i)
    if (c->is_held[i]) {
      u[i] = c->held[i];
      u[LAGRANGE_K + i] = 0.0;
      u[2 * LAGRANGE_K + i] = 0.0;
    }
}

/* The tapes' input vector [t, q, v, u, u_dot, u_ddot, p] at (t, y = (q, v)) into c->tape_in. */
static void lg_pack_inputs(Instance* c, double t, const double* y) {
  double* in = c->tape_in;
  int i;
  in[0] = t;
  for (i = 0; i < LG_NX; ++i) in[1 + i] = y[i];
  lg_current_inputs(c, t, in + 1 + LG_NX);
  for (i = 0; i < LAGRANGE_NP; ++i) in[1 + LG_NX + 3 * LAGRANGE_K + i] = c->p[i];
}

enum { LG_RHS_OK, LG_RHS_SINGULAR, LG_RHS_NOT_FINITE };

/* y' = (q_dot, a) and the multipliers at (t, y): the exported KKT solve (docs/theory.md §4.3). */
static int lg_rhs(Instance* c, double t, const double* y, double* dy) {
  double u[LG_MAX1(3 * LAGRANGE_K)];
  int i;
  lg_current_inputs(c, t, u);
  if (lagrange_dynamics(t, y, y + LAGRANGE_NQ, u, c->p, c->alpha, dy, dy + LAGRANGE_NQ, c->lambda))
    return LG_RHS_SINGULAR;
  for (i = 0; i < LG_NX; ++i)
    if (!isfinite(dy[i])) return LG_RHS_NOT_FINITE;
  return LG_RHS_OK;
}

/* In this order: each needs the ones before it. */
/* clang-format off */
#include "fmu_constraints.c"
#include "fmu_events.c"
#include "fmu_dop853.c"
#include "fmu_fmi2.c"
/* clang-format on */
