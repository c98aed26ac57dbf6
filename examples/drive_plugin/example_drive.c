/*
 * An example netmc drive plugin, and the skeleton of a real one: a CiA 402 servo drive whose
 * "device" is a model integrated in real time. Copy it, keep the state machine and the calls,
 * and replace the model with your fieldbus: every place a real driver would talk to its device
 * (open the master, exchange process data, convert units) says so in a comment marked DEVICE.
 *
 * The model is paper 001's servo axis in speed mode without friction (netmc's seed001 plant,
 * X axis): x'' = a2 x' + b u with a2 = -20 1/s and b = 20 (m/s^2) per input unit, integrated
 * exactly on CLOCK_MONOTONIC whenever netmc calls (cycle, read, every write).
 *
 * What it does, as a drive does:
 * - CiA 402's device state machine: Switch on disabled -> Ready to switch on -> Switched on ->
 *   Operation enabled, quick stop (option code 2: ramp down at the quick stop deceleration,
 *   then Switch on disabled), fault (a fault reaction on the same ramp, then Fault) and fault
 *   reset on bit 7's rising edge.
 * - CST (the job's mode): the torque target is the model's input u, held until the next one.
 * - CSP: its own position loop (critically damped, 5 Hz), so that netmc can move the axis to
 *   an iteration's start position.
 * - Faults: the master silent for longer than `watchdog` seconds while enabled (error 0x8100,
 *   as a fieldbus watchdog raises it), or a model state that is no longer finite (0xFF01).
 *
 * Configuration (plugin:libexample_drive.so:key=value,...): a2 (1/s, -1000..0), b ((m/s^2)
 * per input unit, > 0), position (m, where the axis stands at start), watchdog (s, 0 = off).
 *
 * Threading: netmc calls one drive from one thread; each drive keeps all of its state in its
 * own struct, so several drives (axes) from this plugin can run side by side.
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <netmc/drive_plugin.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* CiA 402 power states, device side. */
enum power_state {
  NOT_READY_TO_SWITCH_ON,
  SWITCH_ON_DISABLED,
  READY_TO_SWITCH_ON,
  SWITCHED_ON,
  OPERATION_ENABLED,
  QUICK_STOP_ACTIVE,
  FAULT_REACTION_ACTIVE,
  FAULT
};

/* Statusword (0x6041) bits. */
#define SW_READY_TO_SWITCH_ON 0x0001u
#define SW_SWITCHED_ON 0x0002u
#define SW_OPERATION_ENABLED 0x0004u
#define SW_FAULT 0x0008u
#define SW_VOLTAGE_ENABLED 0x0010u
#define SW_QUICK_STOP 0x0020u /* 0: a quick stop is active */
#define SW_SWITCH_ON_DISABLED 0x0040u
#define SW_REMOTE 0x0200u
#define SW_TARGET_REACHED 0x0400u

/* Controlword (0x6040) bits. */
#define CW_SWITCH_ON 0x0001u
#define CW_ENABLE_VOLTAGE 0x0002u
#define CW_QUICK_STOP 0x0004u /* 0: quick stop */
#define CW_ENABLE_OPERATION 0x0008u
#define CW_FAULT_RESET 0x0080u

/* Error codes (0x603F). */
#define ERROR_COMMUNICATION 0x8100u
#define ERROR_MODEL_NOT_FINITE 0xFF01u

/* The drive's own loops: their period, bandwidths and windows. */
static const double kLoopPeriodS = 250e-6;
static const double kPositionLoopRadS = 2.0 * 3.14159265358979323846 * 5.0;
static const double kVelocityLoopRadS = 2.0 * 3.14159265358979323846 * 40.0;
static const double kPositionWindowM = 1e-6;  /* CSP: target reached within this */
static const double kStandstillM_S = 1e-3;    /* a ramp ends below this speed */
static const double kQuickStopTimeoutS = 1.0; /* after the ramp's planned end */

struct netmc_drive {
  /* Configuration. */
  double a2, b;      /* x'' = a2 x' + b u */
  double watchdog_s; /* 0: no watchdog */

  /* The device as the master sees it. */
  int opened;
  enum power_state state;
  uint16_t last_controlword;
  uint16_t error_code;
  int8_t mode;
  double target_position_m;
  double target_torque;
  double quick_stop_deceleration_m_s2;
  double ramp_start_s, ramp_start_velocity_m_s;
  double last_call_s; /* the master's last call (watchdog) */

  /* DEVICE: the model stands in for the real axis. Its state at time_s (CLOCK_MONOTONIC). */
  double time_s;
  double position_m, velocity_m_s;
  double input;       /* u now */
  double next_loop_s; /* when the drive's loops act next */
};

/* printf's format checks on the error messages, where the compiler has them. */
#if defined(__GNUC__)
#define PRINTF_LIKE(format_index, first_argument) __attribute__((format(printf, format_index, first_argument)))
#else
#define PRINTF_LIKE(format_index, first_argument)
#endif

/* The reason for a failure into the caller's error buffer (bounded, NUL-terminated). */
PRINTF_LIKE(3, 4) static int fail(char* error, size_t error_size, const char* format, ...) {
  if (error != NULL && error_size > 0) {
    va_list args;
    va_start(args, format);
    vsnprintf(error, error_size, format, args);
    va_end(args);
  }
  return NETMC_DRIVE_FAILED;
}

static double now_s(void) {
  struct timespec now;
  clock_gettime(CLOCK_MONOTONIC, &now);
  return (double)now.tv_sec + 1e-9 * (double)now.tv_nsec;
}

static int power_on(const netmc_drive* d) {
  return d->state == OPERATION_ENABLED || d->state == QUICK_STOP_ACTIVE || d->state == FAULT_REACTION_ACTIVE;
}

static int ramping(const netmc_drive* d) { return d->state == QUICK_STOP_ACTIVE || d->state == FAULT_REACTION_ACTIVE; }

/* Whether the drive's own loops set the input (otherwise it is the torque target, or none). */
static int loops_active(const netmc_drive* d) {
  return ramping(d) || (d->state == OPERATION_ENABLED && d->mode == NETMC_DRIVE_MODE_CSP);
}

/* DEVICE: one exact step of x'' = a2 x' + b u with u held (a real drive has no such thing: its
   axis moves by itself). */
static void model_step(netmc_drive* d, double dt) {
  const double acceleration = d->b * d->input; /* b u */
  const double x0 = d->position_m, v0 = d->velocity_m_s;
  if (d->a2 == 0.0) {
    d->position_m = x0 + v0 * dt + 0.5 * acceleration * dt * dt;
    d->velocity_m_s = v0 + acceleration * dt;
  } else {
    const double phi = expm1(d->a2 * dt) / d->a2; /* integral of e^(a2 s) over [0, dt] */
    const double settled = -acceleration / d->a2; /* the speed u settles at */
    d->position_m = x0 + settled * dt + (v0 - settled) * phi;
    d->velocity_m_s = v0 + (v0 - settled) * d->a2 * phi;
  }
  if (!isfinite(d->position_m) || !isfinite(d->velocity_m_s)) {
    /* The model broke down: no ramp can act on it. Straight to Fault, at rest where it was. */
    d->position_m = isfinite(x0) ? x0 : 0.0;
    d->velocity_m_s = 0.0;
    d->input = 0.0;
    d->target_torque = 0.0;
    d->state = FAULT;
    d->error_code = ERROR_MODEL_NOT_FINITE;
  }
}

static void start_ramp(netmc_drive* d) {
  d->ramp_start_s = d->time_s;
  d->ramp_start_velocity_m_s = d->velocity_m_s;
  d->next_loop_s = d->time_s; /* the ramp's loop acts at once */
}

/* A fault the drive detects (13): a fault reaction on the quick stop ramp, then Fault. */
static void raise_fault(netmc_drive* d, uint16_t code) {
  if (d->state == FAULT_REACTION_ACTIVE || d->state == FAULT) return;
  d->error_code = code;
  if (power_on(d)) {
    d->state = FAULT_REACTION_ACTIVE;
    start_ramp(d);
  } else {
    d->state = FAULT;
  }
}

/* One period of the drive's loops: the input that acts until the next. */
static void run_loops(netmc_drive* d) {
  const double v = d->velocity_m_s;
  if (ramping(d)) {
    /* A velocity reference from the ramp's start speed to zero at the quick stop deceleration,
       followed by a velocity loop with the ramp's deceleration fed forward. */
    const double a = d->quick_stop_deceleration_m_s2;
    const double elapsed = d->time_s - d->ramp_start_s;
    const double sign = d->ramp_start_velocity_m_s < 0.0 ? -1.0 : 1.0;
    const double speed = fmax(0.0, fabs(d->ramp_start_velocity_m_s) - a * elapsed);
    const double feedforward = speed > 0.0 ? -sign * a : 0.0;
    d->input = (feedforward + kVelocityLoopRadS * (sign * speed - v) - d->a2 * v) / d->b;
    const double ramp_s = fabs(d->ramp_start_velocity_m_s) / a;
    if ((speed == 0.0 && fabs(v) < kStandstillM_S) || elapsed > ramp_s + kQuickStopTimeoutS) {
      d->state = d->state == QUICK_STOP_ACTIVE ? SWITCH_ON_DISABLED : FAULT; /* 12, 14 */
      d->input = 0.0;
    }
    return;
  }
  /* CSP: x'' = w^2 (target - x) - 2 w x', critically damped at w (the plant's a2 cancelled). */
  d->input = (kPositionLoopRadS * kPositionLoopRadS * (d->target_position_m - d->position_m) -
              (2.0 * kPositionLoopRadS + d->a2) * v) /
             d->b;
}

/* DEVICE: brings the model to `until_s`, the loops acting on their period. A real driver has
   nothing to integrate: its loops run in the drive. */
static void advance(netmc_drive* d, double until_s) {
  while (d->time_s < until_s) {
    if (!loops_active(d)) {
      d->input = d->state == OPERATION_ENABLED && d->mode == NETMC_DRIVE_MODE_CST ? d->target_torque : 0.0;
      model_step(d, until_s - d->time_s);
      d->time_s = until_s;
      break;
    }
    if (d->time_s >= d->next_loop_s) {
      run_loops(d);
      d->next_loop_s = d->time_s + kLoopPeriodS;
      if (!loops_active(d)) continue; /* a ramp ended: the rest without loops */
    }
    const double step_end = fmin(until_s, d->next_loop_s);
    model_step(d, step_end - d->time_s);
    d->time_s = step_end;
  }
}

/* Every call from the master: the drive's time catches up with the clock, and the watchdog
   checks the master's silence since its last call. */
static void catch_up(netmc_drive* d) {
  const double now = now_s();
  if (d->watchdog_s > 0.0 && d->state == OPERATION_ENABLED && now - d->last_call_s > d->watchdog_s) {
    advance(d, d->last_call_s + d->watchdog_s);
    raise_fault(d, ERROR_COMMUNICATION);
  }
  advance(d, now);
  d->last_call_s = now;
}

static uint16_t state_bits(enum power_state state) {
  switch (state) {
    case NOT_READY_TO_SWITCH_ON: return 0;
    case SWITCH_ON_DISABLED: return SW_SWITCH_ON_DISABLED;
    case READY_TO_SWITCH_ON: return SW_QUICK_STOP | SW_VOLTAGE_ENABLED | SW_READY_TO_SWITCH_ON;
    case SWITCHED_ON: return SW_QUICK_STOP | SW_VOLTAGE_ENABLED | SW_READY_TO_SWITCH_ON | SW_SWITCHED_ON;
    case OPERATION_ENABLED:
      return SW_QUICK_STOP | SW_VOLTAGE_ENABLED | SW_READY_TO_SWITCH_ON | SW_SWITCHED_ON | SW_OPERATION_ENABLED;
    case QUICK_STOP_ACTIVE: return SW_VOLTAGE_ENABLED | SW_READY_TO_SWITCH_ON | SW_SWITCHED_ON | SW_OPERATION_ENABLED;
    case FAULT_REACTION_ACTIVE:
      return SW_VOLTAGE_ENABLED | SW_FAULT | SW_READY_TO_SWITCH_ON | SW_SWITCHED_ON | SW_OPERATION_ENABLED;
    case FAULT: return SW_FAULT;
  }
  return 0;
}

static uint16_t statusword(const netmc_drive* d) {
  unsigned word = state_bits(d->state) | SW_REMOTE;
  if (d->state == OPERATION_ENABLED &&
      (d->mode != NETMC_DRIVE_MODE_CSP || fabs(d->position_m - d->target_position_m) <= kPositionWindowM)) {
    word |= SW_TARGET_REACHED;
  }
  return (uint16_t)word;
}

/* Entering Operation enabled: a drive enables where it stands, with no stale target. */
static void enter_operation_enabled(netmc_drive* d) {
  d->state = OPERATION_ENABLED;
  d->target_position_m = d->position_m;
  d->target_torque = 0.0;
  d->next_loop_s = d->time_s;
}

/* The controlword's command by CiA 402's precedence: bit 1 low (disable voltage) over bit 2 low
   (quick stop) over bit 0 low (shutdown) over bit 3 low (switch on); else enable operation. */
static void apply_controlword(netmc_drive* d, uint16_t word) {
  const int reset_edge = (word & CW_FAULT_RESET) && !(d->last_controlword & CW_FAULT_RESET);
  const int disable_voltage = !(word & CW_ENABLE_VOLTAGE);
  const int quick_stop = !disable_voltage && !(word & CW_QUICK_STOP);
  const int shutdown = !disable_voltage && !quick_stop && !(word & CW_SWITCH_ON);
  const int switch_on = !disable_voltage && !quick_stop && !shutdown && !(word & CW_ENABLE_OPERATION);
  const int enable_operation = !disable_voltage && !quick_stop && !shutdown && !switch_on;
  d->last_controlword = word;
  switch (d->state) {
    case FAULT:
      if (reset_edge) { /* 15 */
        d->state = SWITCH_ON_DISABLED;
        d->error_code = 0;
      }
      break;
    case NOT_READY_TO_SWITCH_ON:
    case FAULT_REACTION_ACTIVE: break; /* only the drive moves on from these */
    case SWITCH_ON_DISABLED:
      if (shutdown) d->state = READY_TO_SWITCH_ON; /* 2 */
      break;
    case READY_TO_SWITCH_ON:
      if (switch_on) d->state = SWITCHED_ON;                            /* 3 */
      if (enable_operation) enter_operation_enabled(d);                 /* 3 + 4 */
      if (disable_voltage || quick_stop) d->state = SWITCH_ON_DISABLED; /* 7 */
      break;
    case SWITCHED_ON:
      if (enable_operation) enter_operation_enabled(d);                 /* 4 */
      if (shutdown) d->state = READY_TO_SWITCH_ON;                      /* 6 */
      if (disable_voltage || quick_stop) d->state = SWITCH_ON_DISABLED; /* 10 */
      break;
    case OPERATION_ENABLED:
      if (switch_on) d->state = SWITCHED_ON;              /* 5 */
      if (shutdown) d->state = READY_TO_SWITCH_ON;        /* 8 */
      if (disable_voltage) d->state = SWITCH_ON_DISABLED; /* 9 */
      if (quick_stop) {                                   /* 11 */
        d->state = QUICK_STOP_ACTIVE;
        start_ramp(d);
      }
      break;
    case QUICK_STOP_ACTIVE:
      if (disable_voltage) d->state = SWITCH_ON_DISABLED; /* 12 */
      break;
  }
}

static int mode_supported(int8_t mode) { return mode == NETMC_DRIVE_MODE_CST || mode == NETMC_DRIVE_MODE_CSP; }

/* A number from a setting, whole and finite, within [min, max]. */
static int parse_number(const netmc_drive_setting* setting, double min, double max, double* out, char* error,
                        size_t error_size) {
  char* end = NULL;
  const double value = strtod(setting->value, &end);
  if (end == setting->value || *end != '\0' || !isfinite(value)) {
    return fail(error, error_size, "%s=%s is not a number", setting->key, setting->value);
  }
  if (value < min || value > max) {
    return fail(error, error_size, "%s=%s is outside [%g, %g]", setting->key, setting->value, min, max);
  }
  *out = value;
  return NETMC_DRIVE_OK;
}

static int example_create(const netmc_drive_setting* settings, size_t setting_count, netmc_drive** drive, char* error,
                          size_t error_size) {
  double a2 = -20.0, b = 20.0, position_m = 0.0, watchdog_s = 0.0;
  for (size_t i = 0; i < setting_count; ++i) {
    const netmc_drive_setting* s = &settings[i];
    int status;
    if (strcmp(s->key, "a2") == 0) {
      status = parse_number(s, -1000.0, 0.0, &a2, error, error_size);
    } else if (strcmp(s->key, "b") == 0) {
      status = parse_number(s, 1e-9, 1e9, &b, error, error_size);
    } else if (strcmp(s->key, "position") == 0) {
      status = parse_number(s, -1e3, 1e3, &position_m, error, error_size);
    } else if (strcmp(s->key, "watchdog") == 0) {
      status = parse_number(s, 0.0, 60.0, &watchdog_s, error, error_size);
    } else {
      status = fail(error, error_size, "unknown key '%s' (keys: a2, b, position, watchdog)", s->key);
    }
    if (status != NETMC_DRIVE_OK) return status;
  }
  netmc_drive* d = calloc(1, sizeof *d);
  if (d == NULL) return fail(error, error_size, "out of memory");
  d->a2 = a2;
  d->b = b;
  d->watchdog_s = watchdog_s;
  d->state = NOT_READY_TO_SWITCH_ON;
  d->mode = NETMC_DRIVE_MODE_CST;
  d->quick_stop_deceleration_m_s2 = 1.0;
  d->position_m = position_m;
  *drive = d;
  return NETMC_DRIVE_OK;
}

static void example_destroy(netmc_drive* d) { free(d); }

static int example_describe(netmc_drive* d, char* text, size_t text_size, char* error, size_t error_size) {
  (void)error;
  (void)error_size;
  snprintf(text, text_size, "example drive: x'' = %g x' + %g u in real time, CST and CSP", d->a2, d->b);
  return NETMC_DRIVE_OK;
}

static int example_job_mode(netmc_drive* d, int8_t* mode, char* error, size_t error_size) {
  (void)d;
  (void)error;
  (void)error_size;
  *mode = NETMC_DRIVE_MODE_CST;
  return NETMC_DRIVE_OK;
}

static int example_supported_modes(netmc_drive* d, uint32_t* modes, char* error, size_t error_size) {
  (void)d;
  (void)error;
  (void)error_size;
  *modes = NETMC_DRIVE_MODE_BIT(NETMC_DRIVE_MODE_CST) | NETMC_DRIVE_MODE_BIT(NETMC_DRIVE_MODE_CSP);
  return NETMC_DRIVE_OK;
}

static int example_open(netmc_drive* d, char* error, size_t error_size) {
  if (d->opened) return fail(error, error_size, "the drive is already open");
  /* DEVICE: open the fieldbus master (ecx_init on the interface, a CAN socket, the DAQ card),
     find the device, check its identity (vendor, product code), map its PDOs (controlword,
     mode, targets; statusword, actual values, error code) and start the cyclic exchange.
     Fail here, with a reason an operator can act on, rather than at the first job. */
  d->opened = 1;
  d->time_s = now_s();
  d->last_call_s = d->time_s;
  d->velocity_m_s = 0.0; /* a drive that was closed has come to rest */
  d->input = 0.0;
  d->last_controlword = 0;
  d->error_code = 0;
  d->state = SWITCH_ON_DISABLED; /* 0, 1: initialised */
  return NETMC_DRIVE_OK;
}

static int example_close(netmc_drive* d, char* error, size_t error_size) {
  if (!d->opened) return fail(error, error_size, "the drive is not open");
  /* DEVICE: write controlword 0 (disable voltage), let it reach the device, stop the cyclic
     exchange and close the master. */
  catch_up(d);
  d->state = NOT_READY_TO_SWITCH_ON;
  d->opened = 0;
  return NETMC_DRIVE_OK;
}

static int example_write_controlword(netmc_drive* d, uint16_t word, char* error, size_t error_size) {
  if (!d->opened) return fail(error, error_size, "the drive is not open");
  catch_up(d);
  /* DEVICE: the controlword goes into the next outputs (RxPDO); the device's state machine
     answers in the statusword a cycle or two later. Here it answers at once. */
  apply_controlword(d, word);
  return NETMC_DRIVE_OK;
}

static int example_write_mode(netmc_drive* d, int8_t mode, char* error, size_t error_size) {
  if (!d->opened) return fail(error, error_size, "the drive is not open");
  if (!mode_supported(mode)) return fail(error, error_size, "mode %d is not supported (CST 10 and CSP 8 are)", mode);
  catch_up(d);
  if (mode == d->mode) return NETMC_DRIVE_OK;
  /* DEVICE: modes of operation (0x6060) in the outputs; the device confirms in 0x6061. */
  d->mode = mode;
  /* No stale target acts in the new mode: CSP holds where the axis stands, CST starts at 0. */
  d->target_position_m = d->position_m;
  d->target_torque = 0.0;
  d->next_loop_s = d->time_s;
  return NETMC_DRIVE_OK;
}

static int example_write_target(netmc_drive* d, int8_t mode, double value, char* error, size_t error_size) {
  if (!d->opened) return fail(error, error_size, "the drive is not open");
  if (!mode_supported(mode)) return fail(error, error_size, "mode %d is not supported (CST 10 and CSP 8 are)", mode);
  if (!isfinite(value)) return fail(error, error_size, "target %g is not finite", value);
  catch_up(d); /* the previous target acts until now */
  /* DEVICE: convert to the device's units (m to counts for 0x607A, the input to per mille of
     rated torque for 0x6071) and put it into the next outputs. */
  if (mode == NETMC_DRIVE_MODE_CSP) {
    d->target_position_m = value;
  } else {
    d->target_torque = value;
  }
  return NETMC_DRIVE_OK;
}

static int example_read(netmc_drive* d, netmc_drive_feedback* feedback, char* error, size_t error_size) {
  if (!d->opened) return fail(error, error_size, "the drive is not open");
  catch_up(d);
  /* DEVICE: decode the last inputs (TxPDO): statusword, error code, actual position and
     velocity, converted from counts to m and m/s. */
  feedback->position_m = d->position_m;
  feedback->velocity_m_s = d->velocity_m_s;
  feedback->has_velocity = 1;
  feedback->statusword = statusword(d);
  feedback->error_code = d->error_code;
  return NETMC_DRIVE_OK;
}

static int example_cycle(netmc_drive* d, double time_s, char* error, size_t error_size) {
  (void)time_s; /* the node's job time; this drive keeps its own clock, as hardware does */
  if (!d->opened) return fail(error, error_size, "the drive is not open");
  /* DEVICE: one process data exchange: send the outputs, receive the inputs, check the
     working counter (a wrong one is a failure to report here). */
  catch_up(d);
  return NETMC_DRIVE_OK;
}

static int example_write_quick_stop_deceleration(netmc_drive* d, double deceleration_m_s2, char* error,
                                                 size_t error_size) {
  if (!d->opened) return fail(error, error_size, "the drive is not open");
  if (!(deceleration_m_s2 > 0.0) || !isfinite(deceleration_m_s2)) {
    return fail(error, error_size, "quick stop deceleration %g m/s^2 is not positive", deceleration_m_s2);
  }
  catch_up(d);
  /* DEVICE: an SDO write of 0x6085 (in the device's units), at open or between jobs. */
  d->quick_stop_deceleration_m_s2 = deceleration_m_s2;
  return NETMC_DRIVE_OK;
}

/* The one exported symbol. */
NETMC_DRIVE_PLUGIN_EXPORT const netmc_drive_plugin_table netmc_drive_plugin = {
    NETMC_DRIVE_PLUGIN_ABI_VERSION,
    sizeof(netmc_drive_plugin_table),
    example_create,
    example_destroy,
    example_describe,
    example_job_mode,
    example_supported_modes,
    example_open,
    example_close,
    example_write_controlword,
    example_write_mode,
    example_write_target,
    example_read,
    example_cycle,
    example_write_quick_stop_deceleration,
};
