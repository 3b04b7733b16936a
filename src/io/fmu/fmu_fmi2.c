/* Part of the FMU that `lagrange export --fmu` writes (docs/fmu.md): the FMI 2.0 functions.
   Included by lagrange_fmu.c. Value references are laid out in lagrange_fmu_model.h (LG_VR_*). */

#define LG_NOT_FAILED(c, fn)                                                                   \
  do {                                                                                         \
    if (!(c)) return fmi2Error;                                                                \
    if ((c)->phase == LG_FAILED) {                                                             \
      lg_log_error((c), "%s: an earlier call failed; call fmi2Reset or fmi2FreeInstance", fn); \
      return fmi2Error;                                                                        \
    }                                                                                          \
  } while (0)

/* 1 when the instance is in one of the phases in `allowed` (a bit mask), else an error. */
static int lg_in_phase(Instance* c, int allowed, const char* fn) {
  static const char* names[] = {
      "instantiated", "initialization mode", "event mode", "continuous-time mode",
      "step mode",    "terminated",          "failed"};
  if (allowed & (1 << c->phase)) return 1;
  lg_log_error(c, "%s: not allowed in %s", fn, names[c->phase]);
  return 0;
}
#define LG_BIT(p) (1 << (p))
#define LG_SETUP (LG_BIT(LG_INSTANTIATED) | LG_BIT(LG_INITIALIZATION))
#define LG_RUNNING (LG_BIT(LG_EVENT) | LG_BIT(LG_CONTINUOUS) | LG_BIT(LG_STEPPING))

/* Moves the instance from one of the phases in `from` (a bit mask) to `to`; an error otherwise. */
static fmi2Status lg_transition(fmi2Component comp, int from, int to, const char* fn) {
  Instance* c = (Instance*)comp;
  LG_NOT_FAILED(c, fn);
  if (!lg_in_phase(c, from, fn)) return fmi2Error;
  c->phase = to;
  return fmi2OK;
}

static void lg_defaults(Instance* c) {
  int i;
  c->t = 0.0;
  for (i = 0; i < LAGRANGE_NQ; ++i) c->y[i] = lg_q0[i];
  for (i = 0; i < LAGRANGE_N; ++i) c->y[LAGRANGE_NQ + i] = lg_v0[i];
  for (i = 0; i < LAGRANGE_NP; ++i) c->p[i] = lg_p0[i];
  for (i = 0; i < LAGRANGE_K; ++i) c->is_held[i] = 0;
  c->alpha = LG_ALPHA;
  c->rtol = LG_RTOL;
  c->atol = LG_ATOL;
  c->project = LG_PROJECT;
  c->h = 0.0;
  c->stopped = 0;
  c->stop_which = -1;
}

const char* fmi2GetTypesPlatform(void) {
  return fmi2TypesPlatform;
}
const char* fmi2GetVersion(void) {
  return fmi2Version;
}

fmi2Component fmi2Instantiate(fmi2String name, fmi2Type type, fmi2String guid, fmi2String resources,
                              const fmi2CallbackFunctions* functions, fmi2Boolean visible,
                              fmi2Boolean logging) {
  Instance* c;
  (void)resources;
  (void)visible;
  if (!functions || !functions->allocateMemory || !functions->freeMemory) return NULL;
  if (!guid || strcmp(guid, LG_GUID) != 0) {
    if (functions->logger)
      functions->logger(functions->componentEnvironment, name ? name : "?", fmi2Error,
                        "logStatusError", "fmi2Instantiate: GUID %s does not match %s",
                        guid ? guid : "(null)", LG_GUID);
    return NULL;
  }
  if (!(type == fmi2ModelExchange ? LG_HAS_ME : LG_HAS_CS)) {
    if (functions->logger)
      functions->logger(functions->componentEnvironment, name ? name : "?", fmi2Error,
                        "logStatusError", "fmi2Instantiate: this FMU was exported without %s",
                        type == fmi2ModelExchange ? "Model Exchange" : "Co-Simulation");
    return NULL;
  }
  c = (Instance*)functions->allocateMemory(1, sizeof(Instance));
  if (!c) return NULL;
  memset(c, 0, sizeof *c);
  c->logger = functions->logger;
  c->allocate = functions->allocateMemory;
  c->release = functions->freeMemory;
  c->env = functions->componentEnvironment;
  snprintf(c->name, sizeof c->name, "%s", name ? name : "");
  c->type = type;
  c->logging = logging;
  c->phase = LG_INSTANTIATED;
  lg_defaults(c);
  return c;
}

void fmi2FreeInstance(fmi2Component comp) {
  Instance* c = (Instance*)comp;
  if (c) c->release(c);
}

fmi2Status fmi2SetDebugLogging(fmi2Component comp, fmi2Boolean on, size_t n,
                               const fmi2String categories[]) {
  Instance* c = (Instance*)comp;
  (void)n;
  (void)categories;
  if (!c) return fmi2Error;
  c->logging = on;
  return fmi2OK;
}

fmi2Status fmi2SetupExperiment(fmi2Component comp, fmi2Boolean tolerance_defined,
                               fmi2Real tolerance, fmi2Real start, fmi2Boolean stop_defined,
                               fmi2Real stop) {
  Instance* c = (Instance*)comp;
  (void)stop_defined;
  (void)stop;
  LG_NOT_FAILED(c, "fmi2SetupExperiment");
  if (!lg_in_phase(c, LG_BIT(LG_INSTANTIATED), "fmi2SetupExperiment")) return fmi2Error;
  if (!isfinite(start) || (tolerance_defined && !(tolerance > 0.0 && tolerance < 1.0))) {
    lg_log_error(c, "fmi2SetupExperiment: expected a finite start time and a tolerance in (0, 1)");
    return fmi2Error;
  }
  c->t = start;
  if (tolerance_defined) c->rtol = tolerance;
  return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
  return lg_transition(c, LG_BIT(LG_INSTANTIATED), LG_INITIALIZATION,
                       "fmi2EnterInitializationMode");
}

/* The initial state made consistent as `lagrange simulate` makes it (docs/theory.md §4.3):
   projected onto C = 0, Cdot = 0 keeping the coordinates the model fixes, rotations made
   orthonormal. */
fmi2Status fmi2ExitInitializationMode(fmi2Component comp) {
  Instance* c = (Instance*)comp;
  int rc = 0;
  LG_NOT_FAILED(c, "fmi2ExitInitializationMode");
  if (!lg_in_phase(c, LG_BIT(LG_INITIALIZATION), "fmi2ExitInitializationMode")) return fmi2Error;
#if LG_NROT > 0
  if (lg_orthonormalize(c->y, 1e-11)) {
    lg_log_error(c, "fmi2ExitInitializationMode: a rotation matrix is singular");
    return fmi2Error;
  }
#endif
#if LAGRANGE_M > 0
  /* 1e-12 as simulate aims for; a state within 1e-9 is accepted (rounding floors of large
     models), one further away is not consistent. */
  rc = lg_project(c, c->t, c->y, lg_fixed, 1e-12);
  if (rc == 2 || (rc == 1 && lg_max_abs(c->tape_out + LG_OUT_C, LAGRANGE_M) > 1e-9)) {
    lg_log_error(c,
                 "fmi2ExitInitializationMode: the initial state cannot be made consistent with "
                 "the constraints (max |C| = %.3g)",
                 lg_max_abs(c->tape_out + LG_OUT_C, LAGRANGE_M));
    return fmi2Error;
  }
#endif
  (void)rc;
  if (lg_rhs(c, c->t, c->y, c->dy) != LG_RHS_OK) {
    lg_log_error(c,
                 "fmi2ExitInitializationMode: the dynamics cannot be evaluated at the initial "
                 "state (singular mass matrix or constraints, or values not finite)");
    return fmi2Error;
  }
#if LG_NZ > 0
  /* the stop conditions' values at the start: one fires when it becomes true after it */
  if (lg_stop_values(c, c->t, c->y, c->g_prev, "fmi2ExitInitializationMode")) return fmi2Error;
#endif
  c->phase = c->type == fmi2ModelExchange ? LG_EVENT : LG_STEPPING;
  return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component comp) {
  Instance* c = (Instance*)comp;
  if (!c) return fmi2Error;
  c->phase = LG_TERMINATED;
  return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component comp) {
  Instance* c = (Instance*)comp;
  if (!c) return fmi2Error;
  lg_defaults(c);
  c->phase = LG_INSTANTIATED;
  return fmi2OK;
}

/* Value `vr` at the current state; 1 for an unknown reference. */
static int lg_get(Instance* c, fmi2ValueReference vr, double* value) {
  if (vr < LG_VR_V + LAGRANGE_N) {
    *value = c->y[vr];
  } else if (vr < LG_VR_P) {
    if (lg_rhs(c, c->t, c->y, c->dy) == LG_RHS_SINGULAR) return 2;
    *value = c->dy[vr - LG_VR_DQ];
  } else if (vr < LG_VR_U) {
    *value = c->p[vr - LG_VR_P];
  } else if (vr < LG_VR_LAMBDA) {
    double u[LG_MAX1(3 * LAGRANGE_K)];
    lg_current_inputs(c, c->t, u);
    *value = u[vr - LG_VR_U];
  } else if (vr < LG_VR_OBS) {
    if (lg_rhs(c, c->t, c->y, c->dy) == LG_RHS_SINGULAR) return 2;
    *value = c->lambda[vr - LG_VR_LAMBDA];
  } else if (vr < LG_VR_ALPHA) {
    int i;
    lg_pack_inputs(c, c->t, c->y);
    lagrange_observables(c->tape_in, c->obs);
    /* kinetic, potential, energy = kinetic + potential, then the model's outputs */
    i = (int)(vr - LG_VR_OBS);
    *value = i < 2 ? c->obs[i] : i == 2 ? c->obs[0] + c->obs[1] : c->obs[i - 1];
  } else if (vr == LG_VR_ALPHA) {
    *value = c->alpha;
  } else if (vr == LG_VR_RTOL) {
    *value = c->rtol;
  } else if (vr == LG_VR_ATOL) {
    *value = c->atol;
  } else {
    return 1;
  }
  return 0;
}

fmi2Status fmi2GetReal(fmi2Component comp, const fmi2ValueReference vr[], size_t n,
                       fmi2Real value[]) {
  Instance* c = (Instance*)comp;
  size_t i;
  if (!c || (n > 0 && (!vr || !value))) return fmi2Error;
  for (i = 0; i < n; ++i) {
    const int rc = lg_get(c, vr[i], &value[i]);
    if (rc) {
      lg_log_error(c,
                   rc == 1 ? "fmi2GetReal: no Real variable has value reference %u"
                           : "fmi2GetReal: the mass matrix or the constraints are singular "
                             "(value reference %u)",
                   vr[i]);
      return fmi2Error;
    }
  }
  return fmi2OK;
}

/* Sets `vr` to `value`, checking that the variable may be set now; 0 or an error logged.
   Parameters are tunable (docs/fmu.md, "Variables"): besides before initialisation, in event mode
   (Model Exchange) and between steps (Co-Simulation), FMI 2.0 §2.2.7. A change after
   initialisation acts from the next evaluation; fmi2DoStep's step size, chosen for the old
   dynamics, is discarded and started afresh (lg_initial_step). */
static int lg_set(Instance* c, fmi2ValueReference vr, double value) {
  const int setup = (1 << c->phase) & LG_SETUP;
  const int tunable = (1 << c->phase) & (LG_SETUP | LG_BIT(LG_EVENT) | LG_BIT(LG_STEPPING));
  if (!isfinite(value)) {
    lg_log_error(c, "fmi2SetReal: value reference %u: expected a finite value, got %g", vr, value);
    return 1;
  }
  if (vr >= LG_VR_P && vr < LG_VR_U && tunable) {
    if (c->p[vr - LG_VR_P] != value) c->h = 0.0;
    c->p[vr - LG_VR_P] = value;
    return 0;
  }
  if ((vr == LG_VR_ALPHA || vr == LG_VR_RTOL || vr == LG_VR_ATOL) && tunable && !setup) c->h = 0.0;
  if (vr < LG_VR_DQ && setup) {
    c->y[vr] = value;
  } else if (vr >= LG_VR_U && vr < LG_VR_U + LAGRANGE_K && lg_external[vr - LG_VR_U] &&
             c->phase != LG_TERMINATED) {
    c->held[vr - LG_VR_U] = value;
    c->is_held[vr - LG_VR_U] = 1;
  } else if (vr == LG_VR_ALPHA && tunable && value >= 0.0) {
    c->alpha = value;
  } else if (vr == LG_VR_RTOL && tunable && value > 0.0 && value < 1.0) {
    c->rtol = value;
  } else if (vr == LG_VR_ATOL && tunable && value > 0.0) {
    c->atol = value;
  } else {
    lg_log_error(c,
                 "fmi2SetReal: value reference %u cannot be set to %g now (unknown, not settable, "
                 "out of range, or a parameter in continuous-time mode or after fmi2Terminate)",
                 vr, value);
    return 1;
  }
  return 0;
}

fmi2Status fmi2SetReal(fmi2Component comp, const fmi2ValueReference vr[], size_t n,
                       const fmi2Real value[]) {
  Instance* c = (Instance*)comp;
  size_t i;
  LG_NOT_FAILED(c, "fmi2SetReal");
  if (n > 0 && (!vr || !value)) return fmi2Error;
  for (i = 0; i < n; ++i)
    if (lg_set(c, vr[i], value[i])) return fmi2Error;
  return fmi2OK;
}

/* No Integer, Boolean or String variables: only empty requests succeed. */
static fmi2Status lg_none(fmi2Component comp, size_t n, const char* fn) {
  Instance* c = (Instance*)comp;
  if (!c) return fmi2Error;
  if (n == 0) return fmi2OK;
  lg_log_error(c, "%s: this FMU has only Real variables", fn);
  return fmi2Error;
}
fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                          fmi2Integer value[]) {
  (void)vr, (void)value;
  return lg_none(c, n, "fmi2GetInteger");
}
fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                          fmi2Boolean value[]) {
  (void)vr, (void)value;
  return lg_none(c, n, "fmi2GetBoolean");
}
fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                         fmi2String value[]) {
  (void)vr, (void)value;
  return lg_none(c, n, "fmi2GetString");
}
fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                          const fmi2Integer value[]) {
  (void)vr, (void)value;
  return lg_none(c, n, "fmi2SetInteger");
}
fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                          const fmi2Boolean value[]) {
  (void)vr, (void)value;
  return lg_none(c, n, "fmi2SetBoolean");
}
fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                         const fmi2String value[]) {
  (void)vr, (void)value;
  return lg_none(c, n, "fmi2SetString");
}

/* fmi2GetFMUstate: a copy of the whole instance (it holds no pointers but the callbacks). */
fmi2Status fmi2GetFMUstate(fmi2Component comp, fmi2FMUstate* state) {
  Instance* c = (Instance*)comp;
  Instance* copy;
  if (!c || !state) return fmi2Error;
  copy = *state ? (Instance*)*state : (Instance*)c->allocate(1, sizeof(Instance));
  if (!copy) {
    lg_log_error(c, "fmi2GetFMUstate: out of memory");
    return fmi2Error;
  }
  memcpy(copy, c, sizeof *c);
  *state = copy;
  return fmi2OK;
}

fmi2Status fmi2SetFMUstate(fmi2Component comp, fmi2FMUstate state) {
  Instance* c = (Instance*)comp;
  Instance keep;
  if (!c || !state) return fmi2Error;
  memcpy(&keep, c, sizeof keep);
  memcpy(c, state, sizeof *c);
  c->logger = keep.logger;
  c->allocate = keep.allocate;
  c->release = keep.release;
  c->env = keep.env;
  memcpy(c->name, keep.name, sizeof c->name);
  c->logging = keep.logging;
  return fmi2OK;
}

fmi2Status fmi2FreeFMUstate(fmi2Component comp, fmi2FMUstate* state) {
  Instance* c = (Instance*)comp;
  if (!c || !state) return fmi2Error;
  if (*state) c->release(*state);
  *state = NULL;
  return fmi2OK;
}

/* Not offered (modelDescription.xml says so): each logs why and returns fmi2Error. */
static fmi2Status lg_unsupported(fmi2Component comp, const char* fn) {
  Instance* c = (Instance*)comp;
  if (c) {
    const int phase = c->phase;
    lg_log_error(c, "%s: not supported by this FMU (see its modelDescription.xml)", fn);
    c->phase = phase; /* the instance itself is fine */
  }
  return fmi2Error;
}
fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate s, size_t* size) {
  (void)s, (void)size;
  return lg_unsupported(c, "fmi2SerializedFMUstateSize");
}
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate s, fmi2Byte b[], size_t n) {
  (void)s, (void)b, (void)n;
  return lg_unsupported(c, "fmi2SerializeFMUstate");
}
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte b[], size_t n, fmi2FMUstate* s) {
  (void)s, (void)b, (void)n;
  return lg_unsupported(c, "fmi2DeSerializeFMUstate");
}
fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference u[], size_t nu,
                                        const fmi2ValueReference z[], size_t nz,
                                        const fmi2Real du[], fmi2Real dz[]) {
  (void)u, (void)nu, (void)z, (void)nz, (void)du, (void)dz;
  return lg_unsupported(c, "fmi2GetDirectionalDerivative");
}
fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                       const fmi2Integer order[], const fmi2Real value[]) {
  (void)vr, (void)n, (void)order, (void)value;
  return lg_unsupported(c, "fmi2SetRealInputDerivatives");
}
fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                        const fmi2Integer order[], fmi2Real value[]) {
  (void)vr, (void)n, (void)order, (void)value;
  return lg_unsupported(c, "fmi2GetRealOutputDerivatives");
}
fmi2Status fmi2CancelStep(fmi2Component c) {
  return lg_unsupported(c, "fmi2CancelStep");
}

/* ---- Model Exchange ---- */

fmi2Status fmi2EnterEventMode(fmi2Component c) {
  return lg_transition(c, LG_BIT(LG_EVENT) | LG_BIT(LG_CONTINUOUS), LG_EVENT, "fmi2EnterEventMode");
}

/* A stop_when condition that became true since the last event (its indicator was not positive
   then and is now) asks the importer to end the run: terminateSimulation (FMI 2.0 §3.2.2). */
fmi2Status fmi2NewDiscreteStates(fmi2Component comp, fmi2EventInfo* info) {
  Instance* c = (Instance*)comp;
#if LG_NZ > 0
  double g[LG_NZ];
  int i;
#endif
  LG_NOT_FAILED(c, "fmi2NewDiscreteStates");
  if (!info || !lg_in_phase(c, LG_BIT(LG_EVENT), "fmi2NewDiscreteStates")) return fmi2Error;
  info->newDiscreteStatesNeeded = fmi2False;
  info->terminateSimulation = fmi2False;
#if LG_NZ > 0
  if (lg_stop_values(c, c->t, c->y, g, "fmi2NewDiscreteStates")) return fmi2Error;
  for (i = 0; i < LG_NZ; ++i) {
    if (!c->stopped && lg_fired(c->g_prev[i], g[i])) {
      c->stopped = 1;
      c->stop_which = i;
      lg_log_event(c, "fmi2NewDiscreteStates: stop_when %s (%s) became true at t = %.17g",
                   lg_stop_names[i], lg_stop_texts[i], c->t);
    }
    c->g_prev[i] = g[i];
  }
  info->terminateSimulation = c->stopped ? fmi2True : fmi2False;
#endif
  info->nominalsOfContinuousStatesChanged = fmi2False;
  info->valuesOfContinuousStatesChanged = fmi2False;
  info->nextEventTimeDefined = fmi2False;
  info->nextEventTime = 0.0;
  return fmi2OK;
}

fmi2Status fmi2EnterContinuousTimeMode(fmi2Component c) {
  return lg_transition(c, LG_BIT(LG_EVENT), LG_CONTINUOUS, "fmi2EnterContinuousTimeMode");
}

fmi2Status fmi2CompletedIntegratorStep(fmi2Component comp, fmi2Boolean no_set_prior,
                                       fmi2Boolean* enter_event_mode, fmi2Boolean* terminate) {
  Instance* c = (Instance*)comp;
  (void)no_set_prior;
  LG_NOT_FAILED(c, "fmi2CompletedIntegratorStep");
  if (!enter_event_mode || !terminate ||
      !lg_in_phase(c, LG_BIT(LG_CONTINUOUS), "fmi2CompletedIntegratorStep"))
    return fmi2Error;
  *enter_event_mode = fmi2False;
  *terminate = fmi2False;
  return fmi2OK;
}

fmi2Status fmi2SetTime(fmi2Component comp, fmi2Real time) {
  Instance* c = (Instance*)comp;
  LG_NOT_FAILED(c, "fmi2SetTime");
  if (!lg_in_phase(c, LG_SETUP | LG_BIT(LG_EVENT) | LG_BIT(LG_CONTINUOUS), "fmi2SetTime"))
    return fmi2Error;
  if (!isfinite(time)) {
    lg_log_error(c, "fmi2SetTime: expected a finite time, got %g", time);
    return fmi2Error;
  }
  c->t = time;
  return fmi2OK;
}

fmi2Status fmi2SetContinuousStates(fmi2Component comp, const fmi2Real x[], size_t nx) {
  Instance* c = (Instance*)comp;
  size_t i;
  LG_NOT_FAILED(c, "fmi2SetContinuousStates");
  if (!lg_in_phase(c, LG_SETUP | LG_BIT(LG_EVENT) | LG_BIT(LG_CONTINUOUS),
                   "fmi2SetContinuousStates"))
    return fmi2Error;
  if (nx != LG_NX || !x) {
    lg_log_error(c, "fmi2SetContinuousStates: expected %d states, got %u", LG_NX, (unsigned)nx);
    return fmi2Error;
  }
  for (i = 0; i < nx; ++i)
    if (!isfinite(x[i])) {
      lg_log_error(c, "fmi2SetContinuousStates: state %u is not finite", (unsigned)i);
      return fmi2Error;
    }
  for (i = 0; i < nx; ++i) c->y[i] = x[i];
  return fmi2OK;
}

fmi2Status fmi2GetContinuousStates(fmi2Component comp, fmi2Real x[], size_t nx) {
  Instance* c = (Instance*)comp;
  size_t i;
  if (!c || !x || nx != LG_NX) return fmi2Error;
  for (i = 0; i < nx; ++i) x[i] = c->y[i];
  return fmi2OK;
}

fmi2Status fmi2GetDerivatives(fmi2Component comp, fmi2Real dx[], size_t nx) {
  Instance* c = (Instance*)comp;
  int rc;
  size_t i;
  LG_NOT_FAILED(c, "fmi2GetDerivatives");
  if (!dx || nx != LG_NX) {
    lg_log_error(c, "fmi2GetDerivatives: expected %d derivatives, got %u", LG_NX, (unsigned)nx);
    return fmi2Error;
  }
  rc = lg_rhs(c, c->t, c->y, c->dy);
  if (rc != LG_RHS_OK) {
    lg_log_error(c, "fmi2GetDerivatives: at t = %.17g %s", c->t,
                 rc == LG_RHS_SINGULAR ? "the mass matrix or the constraints are singular"
                                       : "the derivatives are not finite");
    return fmi2Error;
  }
  for (i = 0; i < nx; ++i) dx[i] = c->dy[i];
  return fmi2OK;
}

/* The stop_when conditions' g at the current time and state (fmu_events.c). */
fmi2Status fmi2GetEventIndicators(fmi2Component comp, fmi2Real z[], size_t nz) {
  Instance* c = (Instance*)comp;
  LG_NOT_FAILED(c, "fmi2GetEventIndicators");
  if (nz != LG_NZ || (nz > 0 && !z)) {
    lg_log_error(c, "fmi2GetEventIndicators: expected %d event indicators, got %u", LG_NZ,
                 (unsigned)nz);
    return fmi2Error;
  }
#if LG_NZ > 0
  if (lg_stop_values(c, c->t, c->y, z, "fmi2GetEventIndicators")) return fmi2Error;
#endif
  return fmi2OK;
}

fmi2Status fmi2GetNominalsOfContinuousStates(fmi2Component comp, fmi2Real x[], size_t nx) {
  size_t i;
  if (!comp || (nx > 0 && !x)) return fmi2Error;
  for (i = 0; i < nx; ++i) x[i] = 1.0;
  return fmi2OK;
}

/* ---- Co-Simulation ---- */

fmi2Status fmi2DoStep(fmi2Component comp, fmi2Real now, fmi2Real h, fmi2Boolean no_set_prior) {
  Instance* c = (Instance*)comp;
  int rc;
  (void)no_set_prior;
  LG_NOT_FAILED(c, "fmi2DoStep");
  if (!lg_in_phase(c, LG_BIT(LG_STEPPING), "fmi2DoStep")) return fmi2Error;
  if (!(h >= 0.0) || !isfinite(now) || fabs(now - c->t) > 1e-9 * (1.0 + fabs(c->t))) {
    lg_log_error(c,
                 "fmi2DoStep: expected the communication point %.17g and a step >= 0, got %.17g "
                 "and %g",
                 c->t, now, h);
    return fmi2Error;
  }
  if (c->stopped) {
    lg_log_event(c, "fmi2DoStep: the run ended at t = %.17g, where stop_when %s became true", c->t,
                 lg_stop_names[c->stop_which]);
    return fmi2Discard;
  }
  c->t = now;
  rc = h > 0.0 ? lg_integrate(c, now + h) : 0;
  if (rc < 0) return fmi2Error;
  if (rc > 0) {
    /* FMI 2.0 §4.2.3: the slave computed only part of the step and cannot go further; the master
       reads the time with fmi2GetRealStatus(fmi2LastSuccessfulTime) and fmi2Terminated. */
    c->stopped = 1;
    lg_log_event(c, "fmi2DoStep: stop_when %s (%s) became true at t = %.17g",
                 lg_stop_names[c->stop_which], lg_stop_texts[c->stop_which], c->t);
    return fmi2Discard;
  }
  return fmi2OK;
}

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status* value) {
  (void)s, (void)value;
  return lg_unsupported(c, "fmi2GetStatus");
}
fmi2Status fmi2GetRealStatus(fmi2Component comp, const fmi2StatusKind s, fmi2Real* value) {
  Instance* c = (Instance*)comp;
  if (!c || !value || s != fmi2LastSuccessfulTime) return lg_unsupported(comp, "fmi2GetRealStatus");
  *value = c->t;
  return fmi2OK;
}
fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer* value) {
  (void)s, (void)value;
  return lg_unsupported(c, "fmi2GetIntegerStatus");
}
/* fmi2Terminated: whether a stop_when condition ended the run (after fmi2DoStep's fmi2Discard). */
fmi2Status fmi2GetBooleanStatus(fmi2Component comp, const fmi2StatusKind s, fmi2Boolean* value) {
  Instance* c = (Instance*)comp;
  if (!c || !value || s != fmi2Terminated) return lg_unsupported(comp, "fmi2GetBooleanStatus");
  *value = c->stopped ? fmi2True : fmi2False;
  return fmi2OK;
}
fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String* value) {
  (void)s, (void)value;
  return lg_unsupported(c, "fmi2GetStringStatus");
}
