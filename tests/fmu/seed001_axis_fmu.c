/*
 * Paper 001's axis (plant/second_order_axis.hpp) as an FMI 2.0 co-simulation FMU, for netmc's
 * FMU plant tests:
 *   x'' = a1 x + a2 x' + b u - coulomb tanh(x' / coulomb_velocity_scale),
 * parameters a1, a2, b, coulomb, coulomb_velocity_scale, max_substep, x0, v0 (fixed); input u;
 * outputs x, v. It integrates as SecondOrderAxis does, with the same arithmetic, so that it gives
 * the built-in plant's numbers:
 *   - a1 = 0 and no friction: the exact solution over the step,
 *     v' = v + h phi1(a2 h) (a2 v + w), x' = x + h phi1(a2 h) v + h^2 phi2(a2 h) w, w = b u,
 *     phi1(z) = (e^z - 1) / z, phi2(z) = (e^z - 1 - z) / z^2;
 *   - otherwise ceil(h / max_substep) equal sub-steps, each a fifth-order Taylor step
 *     (plant/coulomb_taylor_step.hpp) or, where the friction's argument would move too far, one
 *     classical RK4 step (plant/rk4_integrator.hpp), tanh as plant/smooth_sign.hpp computes it.
 * canGetAndSetFMUstate: the whole simulation state is one plain struct.
 *
 * Build variants (tests/fmu/CMakeLists.txt):
 *   SEED001_FAIL_AT_TIME=t  fmi2DoStep returns fmi2Error for a step that would end after t s;
 *   SEED001_OMIT_DO_STEP    fmi2DoStep is not exported.
 * Only the functions netmc calls, and the FMU state functions, are exported.
 */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "server/fmu/fmi2_api.h"

#define SEED001_EXPORT __attribute__((visibility("default")))
#ifdef SEED001_OMIT_DO_STEP
#define SEED001_UNUSED_WITHOUT_DO_STEP __attribute__((unused)) /* the integrator serves fmi2DoStep only */
#else
#define SEED001_UNUSED_WITHOUT_DO_STEP
#endif

#ifndef SEED001_GUID
#error "SEED001_GUID must be defined (the guid of modelDescription.xml)"
#endif

/* Value references, as modelDescription.xml.in numbers them. */
enum {
  VR_A1,
  VR_A2,
  VR_B,
  VR_COULOMB,
  VR_SCALE,
  VR_MAX_SUBSTEP,
  VR_U,
  VR_X,
  VR_V,
  VR_X0,
  VR_V0,
  VR_COUNT
};

/* FMI 2.0, 4.2.4: the co-simulation states an instance goes through. */
typedef enum { MODE_INSTANTIATED, MODE_INITIALIZATION, MODE_STEPPING, MODE_TERMINATED, MODE_ERROR } Mode;

/* Everything fmi2GetFMUstate saves. */
typedef struct {
  double value[VR_COUNT];
  double time;
  Mode mode;
} SimulationState;

typedef struct {
  SimulationState state;
  fmi2CallbackFunctions functions; /* a copy: the importer's struct need not outlive the call */
  char name[64];
} Seed001Axis;

/* Paper 001's X axis (plant/plant_catalog.cpp, seed001_axis_parameters(0)). */
static void set_defaults(SimulationState* s) {
  memset(s, 0, sizeof *s);
  s->value[VR_A1] = 0.0;
  s->value[VR_A2] = -20.0;
  s->value[VR_B] = 20.0;
  s->value[VR_COULOMB] = 0.060;
  s->value[VR_SCALE] = 1e-3;
  s->value[VR_MAX_SUBSTEP] = 1e-3;
  s->mode = MODE_INSTANTIATED;
}

static void log_error(Seed001Axis* a, const char* message, double value) {
  if (a->functions.logger != NULL) {
    a->functions.logger(a->functions.componentEnvironment, a->name, fmi2Error, "logStatusError", "%s (%g)", message,
                        value);
  }
}

/* plant/smooth_sign.hpp: tanh with one exp, a short series near 0. */
static double smooth_sign(double x) {
  const double a = fabs(x);
  double magnitude;
  if (a < 0.01) {
    const double a2 = a * a;
    magnitude = a * (1.0 + a2 * (-1.0 / 3.0 + a2 * (2.0 / 15.0 - a2 * (17.0 / 315.0))));
  } else if (a < 20.0) {
    const double e = exp(-2.0 * a);
    magnitude = (1.0 - e) / (1.0 + e);
  } else {
    magnitude = 1.0;
  }
  return copysign(magnitude, x);
}

typedef struct {
  double a1, a2, w, c, inv_scale;
} Coefficients;

static double acceleration(const Coefficients* k, double x, double v) {
  return k->a1 * x + k->a2 * v + k->w - k->c * smooth_sign(v * k->inv_scale);
}

/* plant/coulomb_taylor_step.hpp: one fifth-order Taylor step; 0 (state untouched) where the
 * series would not hold. */
static int taylor_step(double* x, double* v, double h, const Coefficients* k) {
  const double t = smooth_sign(*v * k->inv_scale);
  const double v1 = k->a1 * *x + k->a2 * *v + k->w - k->c * t;
  if (!(fabs(v1) * h * k->inv_scale <= 0.1)) return 0;
  const double s_ = 1.0 - t * t;
  const double t2 = t * t;
  const double c1 = -k->c * k->inv_scale;
  const double c2 = c1 * k->inv_scale;
  const double c3 = c2 * k->inv_scale;
  const double c4 = c3 * k->inv_scale;
  const double g1 = c1 * s_;
  const double g2 = c2 * (-2.0 * t * s_);
  const double g3 = c3 * s_ * (6.0 * t2 - 2.0);
  const double g4 = c4 * s_ * t * (16.0 - 24.0 * t2);
  const double damping = k->a2 + g1;
  const double v2 = k->a1 * *v + damping * v1;
  const double v1sq = v1 * v1;
  const double v3 = k->a1 * v1 + damping * v2 + g2 * v1sq;
  const double v4 = k->a1 * v2 + damping * v3 + 3.0 * g2 * v1 * v2 + g3 * v1sq * v1;
  const double v5 = k->a1 * v3 + damping * v4 + g2 * (4.0 * v1 * v3 + 3.0 * v2 * v2) + 6.0 * g3 * v1sq * v2 +
                    g4 * v1sq * v1sq;
  *x += h * (*v + h / 2.0 * (v1 + h / 3.0 * (v2 + h / 4.0 * (v3 + h / 5.0 * v4))));
  *v += h * (v1 + h / 2.0 * (v2 + h / 3.0 * (v3 + h / 4.0 * (v4 + h / 5.0 * v5))));
  return 1;
}

/* plant/rk4_integrator.hpp: one classical RK4 step. */
static void rk4_step(double* x, double* v, double h, const Coefficients* k) {
  const double half = 0.5 * h;
  const double k1x = *v;
  const double k1v = acceleration(k, *x, *v);
  const double k2x = *v + half * k1v;
  const double k2v = acceleration(k, *x + half * k1x, k2x);
  const double k3x = *v + half * k2v;
  const double k3v = acceleration(k, *x + half * k2x, k3x);
  const double k4x = *v + h * k3v;
  const double k4v = acceleration(k, *x + h * k3x, k4x);
  *x += (h / 6.0) * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
  *v += (h / 6.0) * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
}

/* phi1(z) = (e^z - 1) / z and phi2(z) = (e^z - 1 - z) / z^2, by their series where the direct
 * forms would cancel. */
static void phi_functions(double z, double* phi1, double* phi2) {
  if (fabs(z) < 0.5) {
    /* phi1 = sum z^n / (n + 1)!, phi2 = sum z^n / (n + 2)!; 20 terms: 0.5^20 / 22! ~ 1e-27. */
    double term1 = 1.0, term2 = 0.5, sum1 = 0.0, sum2 = 0.0;
    for (int n = 0; n < 20; ++n) {
      sum1 += term1;
      sum2 += term2;
      term1 *= z / (double)(n + 2);
      term2 *= z / (double)(n + 3);
    }
    *phi1 = sum1;
    *phi2 = sum2;
  } else {
    const double e = expm1(z);
    *phi1 = e / z;
    *phi2 = (e - z) / (z * z);
  }
}

/* plant/parameter_checks.cpp substep_count: ceil(duration / max_substep), forgiving round-off. */
static long long substep_count(double duration, double max_substep) {
  const double n = ceil(duration / max_substep * (1.0 - 1e-12));
  return n < 1.0 ? 1 : (long long)n;
}

SEED001_UNUSED_WITHOUT_DO_STEP static void advance(SimulationState* s, double h) {
  const double* p = s->value;
  const double w = p[VR_B] * p[VR_U];
  double x = p[VR_X];
  double v = p[VR_V];
  if (p[VR_COULOMB] == 0.0 && p[VR_A1] == 0.0) {
    double phi1, phi2;
    phi_functions(p[VR_A2] * h, &phi1, &phi2);
    s->value[VR_X] = x + h * phi1 * v + h * h * phi2 * w;
    s->value[VR_V] = v + h * phi1 * (p[VR_A2] * v + w);
    return;
  }
  const Coefficients k = {p[VR_A1], p[VR_A2], w, p[VR_COULOMB], 1.0 / p[VR_SCALE]};
  const long long n = substep_count(h, p[VR_MAX_SUBSTEP]);
  const double step = h / (double)n;
  for (long long i = 0; i < n; ++i) {
    if (!taylor_step(&x, &v, step, &k)) rk4_step(&x, &v, step, &k);
  }
  s->value[VR_X] = x;
  s->value[VR_V] = v;
}

static int is_parameter(fmi2ValueReference vr) { return vr <= VR_MAX_SUBSTEP || vr == VR_X0 || vr == VR_V0; }

SEED001_EXPORT fmi2GetTypesPlatformTYPE fmi2GetTypesPlatform;
SEED001_EXPORT fmi2GetVersionTYPE fmi2GetVersion;
SEED001_EXPORT fmi2InstantiateTYPE fmi2Instantiate;
SEED001_EXPORT fmi2FreeInstanceTYPE fmi2FreeInstance;
SEED001_EXPORT fmi2SetupExperimentTYPE fmi2SetupExperiment;
SEED001_EXPORT fmi2EnterInitializationModeTYPE fmi2EnterInitializationMode;
SEED001_EXPORT fmi2ExitInitializationModeTYPE fmi2ExitInitializationMode;
SEED001_EXPORT fmi2TerminateTYPE fmi2Terminate;
SEED001_EXPORT fmi2ResetTYPE fmi2Reset;
SEED001_EXPORT fmi2GetRealTYPE fmi2GetReal;
SEED001_EXPORT fmi2SetRealTYPE fmi2SetReal;
SEED001_EXPORT fmi2GetFMUstateTYPE fmi2GetFMUstate;
SEED001_EXPORT fmi2SetFMUstateTYPE fmi2SetFMUstate;
SEED001_EXPORT fmi2FreeFMUstateTYPE fmi2FreeFMUstate;
#ifndef SEED001_OMIT_DO_STEP
SEED001_EXPORT fmi2DoStepTYPE fmi2DoStep;
#endif

const char* fmi2GetTypesPlatform(void) { return "default"; }
const char* fmi2GetVersion(void) { return "2.0"; }

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions* functions,
                              fmi2Boolean visible, fmi2Boolean loggingOn) {
  (void)fmuResourceLocation;
  (void)visible;
  (void)loggingOn;
  if (functions == NULL || functions->allocateMemory == NULL || functions->freeMemory == NULL) return NULL;
  if (fmuType != fmi2CoSimulation || fmuGUID == NULL || strcmp(fmuGUID, SEED001_GUID) != 0) return NULL;
  Seed001Axis* a = (Seed001Axis*)functions->allocateMemory(1, sizeof(Seed001Axis));
  if (a == NULL) return NULL;
  a->functions = *functions;
  strncpy(a->name, instanceName != NULL ? instanceName : "", sizeof a->name - 1);
  set_defaults(&a->state);
  return a;
}

void fmi2FreeInstance(fmi2Component c) {
  Seed001Axis* a = (Seed001Axis*)c;
  if (a != NULL) a->functions.freeMemory(a);
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance,
                               fmi2Real startTime, fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
  Seed001Axis* a = (Seed001Axis*)c;
  (void)toleranceDefined;
  (void)tolerance;
  (void)stopTimeDefined;
  (void)stopTime;
  if (a->state.mode != MODE_INSTANTIATED) return fmi2Error;
  a->state.time = startTime;
  return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
  Seed001Axis* a = (Seed001Axis*)c;
  if (a->state.mode != MODE_INSTANTIATED) return fmi2Error;
  a->state.mode = MODE_INITIALIZATION;
  a->state.value[VR_X] = a->state.value[VR_X0];
  a->state.value[VR_V] = a->state.value[VR_V0];
  return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
  Seed001Axis* a = (Seed001Axis*)c;
  const double* p = a->state.value;
  if (a->state.mode != MODE_INITIALIZATION) return fmi2Error;
  if (!(p[VR_COULOMB] >= 0.0) || !(p[VR_SCALE] > 0.0) || !(p[VR_MAX_SUBSTEP] > 0.0)) {
    log_error(a, "coulomb must be >= 0, coulomb_velocity_scale and max_substep > 0", p[VR_COULOMB]);
    a->state.mode = MODE_ERROR;
    return fmi2Error;
  }
  a->state.value[VR_X] = p[VR_X0];
  a->state.value[VR_V] = p[VR_V0];
  a->state.mode = MODE_STEPPING;
  return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component c) {
  Seed001Axis* a = (Seed001Axis*)c;
  if (a->state.mode != MODE_STEPPING) return fmi2Error;
  a->state.mode = MODE_TERMINATED;
  return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component c) {
  set_defaults(&((Seed001Axis*)c)->state);
  return fmi2OK;
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[]) {
  const Seed001Axis* a = (const Seed001Axis*)c;
  for (size_t i = 0; i < nvr; ++i) {
    if (vr[i] >= VR_COUNT) return fmi2Error;
    value[i] = a->state.value[vr[i]];
  }
  return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[]) {
  Seed001Axis* a = (Seed001Axis*)c;
  const Mode mode = a->state.mode;
  for (size_t i = 0; i < nvr; ++i) {
    if (vr[i] >= VR_COUNT || vr[i] == VR_X || vr[i] == VR_V) return fmi2Error;
    /* FMI 2.0, 2.2.7: fixed parameters only before initialisation ends; the input any time. */
    if (is_parameter(vr[i]) && mode != MODE_INSTANTIATED && mode != MODE_INITIALIZATION) return fmi2Error;
    if (vr[i] == VR_U && (mode == MODE_TERMINATED || mode == MODE_ERROR)) return fmi2Error;
    a->state.value[vr[i]] = value[i];
  }
  return fmi2OK;
}

#ifndef SEED001_OMIT_DO_STEP
fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,
                      fmi2Boolean noSetFMUStatePriorToCurrentPoint) {
  Seed001Axis* a = (Seed001Axis*)c;
  const double t = currentCommunicationPoint;
  const double h = communicationStepSize;
  (void)noSetFMUStatePriorToCurrentPoint;
  if (a->state.mode != MODE_STEPPING) return fmi2Error;
  /* FMI 2.0, 4.2.2: the step starts where the last one ended. */
  if (fabs(t - a->state.time) > 1e-9 * fmax(1.0, fabs(t))) {
    log_error(a, "fmi2DoStep: the communication point is not where the last step ended", a->state.time);
    return fmi2Error;
  }
  if (!(h > 0.0) || !(h / a->state.value[VR_MAX_SUBSTEP] <= 1099511627776.0)) {
    log_error(a, "fmi2DoStep: bad communication step size", h);
    return fmi2Error;
  }
#ifdef SEED001_FAIL_AT_TIME
  if (t + h > SEED001_FAIL_AT_TIME) {
    log_error(a, "fmi2DoStep: the test model fails by design after t", SEED001_FAIL_AT_TIME);
    a->state.mode = MODE_ERROR;
    return fmi2Error;
  }
#endif
  advance(&a->state, h);
  a->state.time = t + h;
  return fmi2OK;
}
#endif

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate* FMUstate) {
  Seed001Axis* a = (Seed001Axis*)c;
  SimulationState* saved = (SimulationState*)*FMUstate;
  if (saved == NULL) {
    saved = (SimulationState*)a->functions.allocateMemory(1, sizeof(SimulationState));
    if (saved == NULL) return fmi2Error;
  }
  *saved = a->state; /* FMI 2.0, 2.1.8: a non-NULL state is overwritten */
  *FMUstate = saved;
  return fmi2OK;
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate FMUstate) {
  Seed001Axis* a = (Seed001Axis*)c;
  if (FMUstate == NULL) return fmi2Error;
  a->state = *(const SimulationState*)FMUstate;
  return fmi2OK;
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate* FMUstate) {
  Seed001Axis* a = (Seed001Axis*)c;
  if (FMUstate != NULL && *FMUstate != NULL) {
    a->functions.freeMemory(*FMUstate);
    *FMUstate = NULL;
  }
  return fmi2OK;
}
