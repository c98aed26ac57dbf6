/*
 * A drive plugin for the loader's refusals, built once per fault (tests/drive/plugin/
 * CMakeLists.txt): FAKE_ABI_VERSION sets the table's version, FAKE_SHORT_TABLE states a size
 * one pointer short, FAKE_NO_ENTRY leaves the entry object out, FAKE_NULL_CYCLE leaves one
 * function null and FAKE_CREATE_FAILS makes create refuse with text no operator should see raw
 * (an escape sequence, a newline, a non-ASCII byte, no NUL before the buffer's end). Every call counts
 * itself in fake_drive_plugin_calls, so a test can see that a refused plugin was never called.
 */
#include <netmc/drive_plugin.h>
#include <stdlib.h>
#include <string.h>

#ifndef FAKE_ABI_VERSION
#define FAKE_ABI_VERSION NETMC_DRIVE_PLUGIN_ABI_VERSION
#endif
#ifdef FAKE_SHORT_TABLE
#define FAKE_TABLE_SIZE (sizeof(netmc_drive_plugin_table) - sizeof(void*))
#else
#define FAKE_TABLE_SIZE sizeof(netmc_drive_plugin_table)
#endif

NETMC_DRIVE_PLUGIN_EXPORT int fake_drive_plugin_calls = 0;

struct netmc_drive {
  int unused;
};

static int fake_create(const netmc_drive_setting* settings, size_t setting_count, netmc_drive** drive, char* error,
                       size_t error_size) {
  (void)settings;
  (void)setting_count;
  ++fake_drive_plugin_calls;
#ifdef FAKE_CREATE_FAILS
  static const char reason[] = "bad\x1b[31m config\n\xc3\xa9";
  memset(error, 'x', error_size); /* no NUL anywhere: the loader must stop at the buffer's end */
  memcpy(error, reason, sizeof reason - 1);
  (void)drive;
  return NETMC_DRIVE_FAILED;
#else
  (void)error;
  (void)error_size;
  *drive = calloc(1, sizeof **drive);
  return *drive != NULL ? NETMC_DRIVE_OK : NETMC_DRIVE_FAILED;
#endif
}

static void fake_destroy(netmc_drive* drive) {
  ++fake_drive_plugin_calls;
  free(drive);
}

static int fake_describe(netmc_drive* drive, char* text, size_t text_size, char* error, size_t error_size) {
  (void)drive;
  (void)text;
  (void)text_size;
  (void)error;
  (void)error_size;
  ++fake_drive_plugin_calls;
  return NETMC_DRIVE_OK;
}

static int fake_job_mode(netmc_drive* drive, int8_t* mode, char* error, size_t error_size) {
  (void)drive;
  (void)error;
  (void)error_size;
  ++fake_drive_plugin_calls;
  *mode = NETMC_DRIVE_MODE_CST;
  return NETMC_DRIVE_OK;
}

static int fake_supported_modes(netmc_drive* drive, uint32_t* modes, char* error, size_t error_size) {
  (void)drive;
  (void)error;
  (void)error_size;
  ++fake_drive_plugin_calls;
  *modes = NETMC_DRIVE_MODE_BIT(NETMC_DRIVE_MODE_CST);
  return NETMC_DRIVE_OK;
}

/* open, close, cycle: nothing to do. */
static int fake_call(netmc_drive* drive, char* error, size_t error_size) {
  (void)drive;
  (void)error;
  (void)error_size;
  ++fake_drive_plugin_calls;
  return NETMC_DRIVE_OK;
}

static int fake_write_controlword(netmc_drive* drive, uint16_t word, char* error, size_t error_size) {
  (void)word;
  return fake_call(drive, error, error_size);
}

static int fake_write_mode(netmc_drive* drive, int8_t mode, char* error, size_t error_size) {
  (void)mode;
  return fake_call(drive, error, error_size);
}

static int fake_write_target(netmc_drive* drive, int8_t mode, double value, char* error, size_t error_size) {
  (void)mode;
  (void)value;
  return fake_call(drive, error, error_size);
}

static int fake_read(netmc_drive* drive, netmc_drive_feedback* feedback, char* error, size_t error_size) {
  (void)feedback;
  return fake_call(drive, error, error_size);
}

#ifndef FAKE_NULL_CYCLE
static int fake_cycle(netmc_drive* drive, double time_s, char* error, size_t error_size) {
  (void)time_s;
  return fake_call(drive, error, error_size);
}
#endif

static int fake_write_quick_stop_deceleration(netmc_drive* drive, double deceleration_m_s2, char* error,
                                              size_t error_size) {
  (void)deceleration_m_s2;
  return fake_call(drive, error, error_size);
}

#ifdef FAKE_NO_ENTRY
/* Everything but the entry object, exported under another name. */
NETMC_DRIVE_PLUGIN_EXPORT const netmc_drive_plugin_table netmc_drive_plugin_misnamed = {
#else
NETMC_DRIVE_PLUGIN_EXPORT const netmc_drive_plugin_table netmc_drive_plugin = {
#endif
    FAKE_ABI_VERSION,
    FAKE_TABLE_SIZE,
    fake_create,
    fake_destroy,
    fake_describe,
    fake_job_mode,
    fake_supported_modes,
    fake_call,
    fake_call,
    fake_write_controlword,
    fake_write_mode,
    fake_write_target,
    fake_read,
#ifdef FAKE_NULL_CYCLE
    NULL,
#else
    fake_cycle,
#endif
    fake_write_quick_stop_deceleration,
};
