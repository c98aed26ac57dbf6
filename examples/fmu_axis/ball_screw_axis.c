/*
 * A ball-screw linear axis as an FMI 2.0 co-simulation FMU: a servo motor turns a screw that
 * moves a table. The drive is current-controlled, so the command u is the motor current (A).
 *
 *   m_eff x'' = torque_constant (2 pi / screw_lead) u - damping x' - coulomb tanh(x' / coulomb_velocity)
 *   m_eff     = mass + rotor_inertia (2 pi / screw_lead)^2   (the rotor's inertia seen at the table)
 *
 * Input u; outputs x (m), v (m/s); parameters as modelDescription.xml.in declares them, in SI
 * units. Each communication step is integrated with classical RK4 in equal sub-steps, short
 * enough for the friction's steep slope near v = 0 (coulomb / coulomb_velocity) and the damping.
 * Only the FMI functions netmc calls are exported.
 */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "server/fmu/fmi2_api.h"

#define EXPORT __attribute__((visibility("default")))

#ifndef BALL_SCREW_AXIS_GUID
#error "BALL_SCREW_AXIS_GUID must be defined (the guid of modelDescription.xml)"
#endif

/* Value references, as modelDescription.xml.in numbers them. */
enum {
  VR_MASS,
  VR_ROTOR_INERTIA,
  VR_SCREW_LEAD,
  VR_TORQUE_CONSTANT,
  VR_DAMPING,
  VR_COULOMB,
  VR_COULOMB_VELOCITY,
  VR_X0,
  VR_V0,
  VR_U,
  VR_X,
  VR_V,
  VR_COUNT
};

static const double kTwoPi = 6.283185307179586;
/* RK4 is stable for h * rate < 2.78 on a linear decay; 0.5 keeps it accurate too. */
static const double kStepTimesRate = 0.5;
static const long long kMaxSubsteps = 1000000;

typedef enum { MODE_INSTANTIATED, MODE_INITIALIZATION, MODE_STEPPING, MODE_TERMINATED, MODE_ERROR } Mode;

typedef struct {
  double value[VR_COUNT];
  Mode mode;
  fmi2CallbackFunctions functions; /* a copy: the importer's struct need not outlive the call */
  char name[64];
} Axis;

static void set_defaults(Axis* a) {
  memset(a->value, 0, sizeof a->value);
  a->value[VR_MASS] = 2.5;               /* kg, table and load */
  a->value[VR_ROTOR_INERTIA] = 1.0e-5;   /* kg m^2, motor rotor and screw */
  a->value[VR_SCREW_LEAD] = 0.01;        /* m per revolution */
  a->value[VR_TORQUE_CONSTANT] = 0.2;    /* N m/A */
  a->value[VR_DAMPING] = 120.0;          /* N s/m */
  a->value[VR_COULOMB] = 2.0;            /* N */
  a->value[VR_COULOMB_VELOCITY] = 1e-3;  /* m/s */
  a->mode = MODE_INSTANTIATED;
}

static void log_error(const Axis* a, const char* message) {
  if (a->functions.logger != NULL) {
    a->functions.logger(a->functions.componentEnvironment, a->name, fmi2Error, "logStatusError", "%s", message);
  }
}

/* The model's coefficients at the table, from the parameters. */
typedef struct {
  double inverse_mass, force_per_ampere, damping, coulomb, coulomb_velocity;
} Dynamics;

static Dynamics dynamics_of(const double* p) {
  const double screw_ratio = kTwoPi / p[VR_SCREW_LEAD]; /* rad of the motor per m of travel */
  const Dynamics d = {1.0 / (p[VR_MASS] + p[VR_ROTOR_INERTIA] * screw_ratio * screw_ratio),
                      p[VR_TORQUE_CONSTANT] * screw_ratio, p[VR_DAMPING], p[VR_COULOMB], p[VR_COULOMB_VELOCITY]};
  return d;
}

/* The table's acceleration (m/s^2) at velocity v under current u. */
static double acceleration(const Dynamics* d, double u, double v) {
  const double friction = d->damping * v + d->coulomb * tanh(v / d->coulomb_velocity);
  return d->inverse_mass * (d->force_per_ampere * u - friction);
}

/* Advances x, v over h with u held; 0 if h needs more sub-steps than kMaxSubsteps. */
static int advance(double* value, double h) {
  const Dynamics d = dynamics_of(value);
  const double rate = d.inverse_mass * (d.damping + d.coulomb / d.coulomb_velocity);
  const double n = fmax(1.0, ceil(h * rate / kStepTimesRate));
  if (!(n <= (double)kMaxSubsteps)) return 0;
  const double s = h / n;
  const double u = value[VR_U];
  double x = value[VR_X];
  double v = value[VR_V];
  for (long long i = 0; i < (long long)n; ++i) {
    const double a1 = acceleration(&d, u, v);
    const double a2 = acceleration(&d, u, v + 0.5 * s * a1);
    const double a3 = acceleration(&d, u, v + 0.5 * s * a2);
    const double a4 = acceleration(&d, u, v + s * a3);
    x += s * (v + s / 6.0 * (a1 + a2 + a3)); /* x' = v, so x's RK4 stages are v's */
    v += s / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
  }
  value[VR_X] = x;
  value[VR_V] = v;
  return 1;
}

static int is_parameter(fmi2ValueReference vr) { return vr <= VR_V0; }

EXPORT fmi2GetTypesPlatformTYPE fmi2GetTypesPlatform;
EXPORT fmi2GetVersionTYPE fmi2GetVersion;
EXPORT fmi2InstantiateTYPE fmi2Instantiate;
EXPORT fmi2FreeInstanceTYPE fmi2FreeInstance;
EXPORT fmi2SetupExperimentTYPE fmi2SetupExperiment;
EXPORT fmi2EnterInitializationModeTYPE fmi2EnterInitializationMode;
EXPORT fmi2ExitInitializationModeTYPE fmi2ExitInitializationMode;
EXPORT fmi2TerminateTYPE fmi2Terminate;
EXPORT fmi2ResetTYPE fmi2Reset;
EXPORT fmi2GetRealTYPE fmi2GetReal;
EXPORT fmi2SetRealTYPE fmi2SetReal;
EXPORT fmi2DoStepTYPE fmi2DoStep;

const char* fmi2GetTypesPlatform(void) { return "default"; }
const char* fmi2GetVersion(void) { return "2.0"; }

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions* functions,
                              fmi2Boolean visible, fmi2Boolean loggingOn) {
  (void)fmuResourceLocation;
  (void)visible;
  (void)loggingOn;
  if (functions == NULL || functions->allocateMemory == NULL || functions->freeMemory == NULL) return NULL;
  if (fmuType != fmi2CoSimulation || fmuGUID == NULL || strcmp(fmuGUID, BALL_SCREW_AXIS_GUID) != 0) return NULL;
  Axis* a = (Axis*)functions->allocateMemory(1, sizeof(Axis));
  if (a == NULL) return NULL;
  a->functions = *functions;
  strncpy(a->name, instanceName != NULL ? instanceName : "", sizeof a->name - 1);
  set_defaults(a);
  return a;
}

void fmi2FreeInstance(fmi2Component c) {
  Axis* a = (Axis*)c;
  if (a != NULL) a->functions.freeMemory(a);
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance,
                               fmi2Real startTime, fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
  (void)toleranceDefined;
  (void)tolerance;
  (void)startTime; /* the model does not depend on time */
  (void)stopTimeDefined;
  (void)stopTime;
  return ((Axis*)c)->mode == MODE_INSTANTIATED ? fmi2OK : fmi2Error;
}

/* FMI 2.0, 4.2.4: each call is allowed in one mode only and moves the instance to the next. */
static fmi2Status transition(Axis* a, Mode from, Mode to) {
  if (a->mode != from) return fmi2Error;
  a->mode = to;
  return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
  return transition((Axis*)c, MODE_INSTANTIATED, MODE_INITIALIZATION);
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
  Axis* a = (Axis*)c;
  const double* p = a->value;
  if (a->mode != MODE_INITIALIZATION) return fmi2Error;
  if (!(p[VR_MASS] > 0.0) || !(p[VR_ROTOR_INERTIA] >= 0.0) || !(p[VR_SCREW_LEAD] > 0.0) ||
      !(p[VR_DAMPING] >= 0.0) || !(p[VR_COULOMB] >= 0.0) || !(p[VR_COULOMB_VELOCITY] > 0.0)) {
    log_error(a, "mass, screw_lead and coulomb_velocity must be > 0; rotor_inertia, damping and coulomb >= 0");
    a->mode = MODE_ERROR;
    return fmi2Error;
  }
  a->value[VR_X] = p[VR_X0];
  a->value[VR_V] = p[VR_V0];
  a->mode = MODE_STEPPING;
  return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component c) { return transition((Axis*)c, MODE_STEPPING, MODE_TERMINATED); }

fmi2Status fmi2Reset(fmi2Component c) {
  set_defaults((Axis*)c);
  return fmi2OK;
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[]) {
  const Axis* a = (const Axis*)c;
  for (size_t i = 0; i < nvr; ++i) {
    if (vr[i] >= VR_COUNT) return fmi2Error;
    value[i] = a->value[vr[i]];
  }
  return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[]) {
  Axis* a = (Axis*)c;
  for (size_t i = 0; i < nvr; ++i) {
    if (vr[i] >= VR_COUNT || vr[i] == VR_X || vr[i] == VR_V) return fmi2Error;
    /* FMI 2.0, 2.2.7: fixed parameters only before initialisation ends; the input any time. */
    if (is_parameter(vr[i]) && a->mode != MODE_INSTANTIATED && a->mode != MODE_INITIALIZATION) return fmi2Error;
    if (a->mode == MODE_TERMINATED || a->mode == MODE_ERROR) return fmi2Error;
    a->value[vr[i]] = value[i];
  }
  return fmi2OK;
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,
                      fmi2Boolean noSetFMUStatePriorToCurrentPoint) {
  Axis* a = (Axis*)c;
  (void)currentCommunicationPoint;
  (void)noSetFMUStatePriorToCurrentPoint;
  if (a->mode != MODE_STEPPING) return fmi2Error;
  if (!(communicationStepSize > 0.0) || !advance(a->value, communicationStepSize)) {
    log_error(a, "fmi2DoStep: the communication step is not positive, or too long for the sub-step bound");
    return fmi2Error;
  }
  return fmi2OK;
}
