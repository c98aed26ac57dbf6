/*
 * netmc's drive plugin ABI, version 1: how a lab's own drive (EtherCAT through SOEM or IgH,
 * CANopen, a DAQ card's +-10 V outputs, ...) plugs in under an axis node without touching
 * netmc. The plugin is a shared object; `netmc-axis --drive plugin:PATH.so[:key=value,...]`
 * loads it and drives it exactly as it drives netmc's own drives (server/drive/drive.hpp): a
 * CiA 402 device taking controlwords, a mode of operation and targets, reporting its
 * statusword, error code and actual values. Everything above the seam (limits, watchdog,
 * latched trips, the CiA 402 master) stays netmc's, whatever the plugin does.
 *
 * Plain C (C99 or later, or C++): build the plugin with `find_package(netmc)` and link
 * `netmc::drive_plugin`, which gives this header as <netmc/drive_plugin.h>.
 *
 * The contract
 * - Entry: the plugin exports one object, `netmc_drive_plugin` (NETMC_DRIVE_PLUGIN_ENTRY), a
 *   const netmc_drive_plugin_table. netmc reads its first two fields, abi_version and
 *   table_size, before it calls anything, and refuses a plugin built for another ABI version or
 *   whose table has another size, or any null function pointer. Those two fields stay first in
 *   every future version; any other change to this header raises the version.
 * - Status: every function but destroy returns NETMC_DRIVE_OK (0) on success. Any other value
 *   is a failure, and the plugin then writes one line of text saying why into `error` (at most
 *   `error_size` bytes, NUL included; netmc passes at least NETMC_DRIVE_PLUGIN_ERROR_SIZE).
 *   netmc reads at most that, shows printable ASCII only and turns the failure into its own
 *   error: a refused create stops the node before it starts, a failure at run time trips the
 *   axis. No C++ exception may leave a plugin function.
 * - Memory: nothing allocated on one side is freed on the other. Strings and arrays netmc
 *   passes in are valid during the call only (copy what you keep); everything a plugin returns
 *   is written into buffers netmc provides. The drive handle is the plugin's own, freed by
 *   destroy.
 * - Threads: netmc calls one drive from one thread at a time, never concurrently, from create
 *   to destroy. A node with several axes may create several drives from one plugin and call
 *   them from different threads: keep state in the drive, or guard what drives share.
 *   A call should return within a fraction of the node's sample period (no blocking waits
 *   longer than the fieldbus's own cycle).
 * - Units: SI across the boundary. Positions in m, velocities in m/s, decelerations in m/s^2,
 *   times in s; a torque target is in the unit of the job's command (the plant's input unit).
 *   A plugin converts to its device's units (counts, 0.1 % of rated torque, volts) below.
 * - Time: a plugin drive runs on its own time (hardware does): the node writes targets as
 *   setpoints arrive, calls cycle() before it reads, and positions the axis between iterations
 *   itself (through CSP where the drive supports it).
 * - Failure of the plugin itself: a plugin runs inside the axis node's process. A crash in it
 *   (a bad pointer, an abort) takes the node down with it: the node is the unit of failure.
 *   The device's own watchdog (the fieldbus's, which a real drive must have armed) then stops
 *   the axis, and the server's silence limit ends the job.
 */
#ifndef NETMC_DRIVE_PLUGIN_H
#define NETMC_DRIVE_PLUGIN_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The ABI this header describes. A plugin stores it in its table's abi_version. */
#define NETMC_DRIVE_PLUGIN_ABI_VERSION 1

/* The name of the one exported object netmc looks up (dlsym). */
#define NETMC_DRIVE_PLUGIN_ENTRY "netmc_drive_plugin"

/* Marks the entry object for export from a plugin built with -fvisibility=hidden. */
#if defined(__GNUC__) || defined(__clang__)
#define NETMC_DRIVE_PLUGIN_EXPORT __attribute__((visibility("default")))
#else
#define NETMC_DRIVE_PLUGIN_EXPORT
#endif

/* Return values. Any non-zero value is a failure; NETMC_DRIVE_FAILED is the one to use. */
#define NETMC_DRIVE_OK 0
#define NETMC_DRIVE_FAILED 1

/* The smallest error and text buffers netmc passes (bytes, NUL included). */
#define NETMC_DRIVE_PLUGIN_ERROR_SIZE 256
#define NETMC_DRIVE_PLUGIN_TEXT_SIZE 256

/* CiA 402 modes of operation (object 0x6060) netmc uses: cyclic synchronous position,
   velocity and torque. */
#define NETMC_DRIVE_MODE_CSP 8
#define NETMC_DRIVE_MODE_CSV 9
#define NETMC_DRIVE_MODE_CST 10
/* A set of modes, as supported_modes reports it: the bit of each mode's code. */
#define NETMC_DRIVE_MODE_BIT(mode) (UINT32_C(1) << (mode))

/* One drive: the plugin's own state, opaque to netmc. */
typedef struct netmc_drive netmc_drive;

/* One key=value pair of the configuration after the path
   (`plugin:PATH.so:ifname=eth0,slave=1`). netmc has checked the key against [A-Za-z0-9_.-];
   the value is printable ASCII without ','. Both are NUL-terminated. */
typedef struct netmc_drive_setting {
  const char* key;
  const char* value;
} netmc_drive_setting;

/* One cyclic read of the drive. netmc zeroes it before read(). */
typedef struct netmc_drive_feedback {
  double position_m;      /* actual position (0x6064), m */
  double velocity_m_s;    /* actual velocity (0x606C), m/s, where has_velocity */
  int32_t has_velocity;   /* non-zero: velocity_m_s is measured; 0: netmc differentiates position */
  uint16_t statusword;    /* 0x6041, as CiA 402 defines its bits */
  uint16_t error_code;    /* 0x603F, 0 when there is no error */
} netmc_drive_feedback;

/* The entry: what a plugin exports as `netmc_drive_plugin`. Each function mirrors one member of
   netmc's Drive interface (server/drive/drive.hpp); `error` and `error_size` are the error
   buffer described above. */
typedef struct netmc_drive_plugin_table {
  /* NETMC_DRIVE_PLUGIN_ABI_VERSION as the plugin was built: first in every version. */
  uint32_t abi_version;
  /* sizeof(netmc_drive_plugin_table) as the plugin was built: second in every version. */
  uint32_t table_size;

  /* Makes a drive from its configuration (`settings[0 .. setting_count)`, in the order given,
     keys unique) and stores it in *drive. Checks the configuration (unknown keys, values out of
     range) and says what is wrong; touches no device yet. On failure *drive is left alone. */
  int (*create)(const netmc_drive_setting* settings, size_t setting_count, netmc_drive** drive, char* error,
                size_t error_size);
  /* Frees the drive and everything it holds. Called once per created drive, last, after close
     if the drive was opened. Cannot fail. */
  void (*destroy)(netmc_drive* drive);

  /* What it is and where, one line into `text` (at most text_size bytes, NUL included):
     "EtherCAT slave 1 on eth0 (Vendor X servo)". netmc asks after create and after open, and
     shows that text in its logs and node list. */
  int (*describe)(netmc_drive* drive, char* text, size_t text_size, char* error, size_t error_size);
  /* The mode a job's commands are written in (NETMC_DRIVE_MODE_*), one of supported_modes. */
  int (*job_mode)(netmc_drive* drive, int8_t* mode, char* error, size_t error_size);
  /* The modes write_mode and write_target accept: NETMC_DRIVE_MODE_BIT of each. netmc writes no
     other mode. */
  int (*supported_modes)(netmc_drive* drive, uint32_t* modes, char* error, size_t error_size);

  /* Connects to the device and checks what can be checked before the first job; the drive
     reports Switch on disabled (or Fault) after it. A failed open leaves nothing open: netmc
     does not call close after it. */
  int (*open)(netmc_drive* drive, char* error, size_t error_size);
  /* Leaves the device with its power stage off where it can, and disconnects. A failure is
     reported in the node's log; netmc goes on to destroy. */
  int (*close)(netmc_drive* drive, char* error, size_t error_size);

  /* Controlword (0x6040), as CiA 402 defines its bits; fault reset acts on bit 7's rising edge. */
  int (*write_controlword)(netmc_drive* drive, uint16_t controlword, char* error, size_t error_size);
  /* Mode of operation (0x6060): NETMC_DRIVE_MODE_*. */
  int (*write_mode)(netmc_drive* drive, int8_t mode, char* error, size_t error_size);
  /* The target of `mode`: position (m, 0x607A), velocity (m/s, 0x60FF) or torque (the job's
     command unit, 0x6071). netmc passes finite values only. */
  int (*write_target)(netmc_drive* drive, int8_t mode, double value, char* error, size_t error_size);
  /* The drive's actual values, statusword and error code. */
  int (*read)(netmc_drive* drive, netmc_drive_feedback* feedback, char* error, size_t error_size);
  /* Called before every read of a sample and every positioning step, with the node's job time
     (s): a drive that needs a cyclic exchange (process data) does it here. */
  int (*cycle)(netmc_drive* drive, double time_s, char* error, size_t error_size);
  /* Quick stop and fault reaction deceleration (0x6085), m/s^2, positive and finite. */
  int (*write_quick_stop_deceleration)(netmc_drive* drive, double deceleration_m_s2, char* error,
                                       size_t error_size);
} netmc_drive_plugin_table;

/* The entry object a plugin defines (and exports) once:
     NETMC_DRIVE_PLUGIN_EXPORT const netmc_drive_plugin_table netmc_drive_plugin = {
         NETMC_DRIVE_PLUGIN_ABI_VERSION, sizeof(netmc_drive_plugin_table), my_create, ...};  */
NETMC_DRIVE_PLUGIN_EXPORT extern const netmc_drive_plugin_table netmc_drive_plugin;

#ifdef __cplusplus
}
#endif

#endif /* NETMC_DRIVE_PLUGIN_H */
