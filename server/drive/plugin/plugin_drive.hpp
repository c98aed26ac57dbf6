#pragma once
// A lab's own drive, loaded from a shared object (--drive plugin:PATH.so[:key=value,...]) that
// speaks netmc's drive plugin ABI (<netmc/drive_plugin.h>). load() refuses, each with one clear
// message, a file that is missing or unreadable, one that is not a loadable shared object, one
// without the entry object, one built for another ABI version or with a table of another size,
// a table with a null function, and a configuration the plugin's create refuses. Nothing of the
// plugin runs before its ABI version and table size are checked (beyond what the dynamic loader
// itself runs). At run time a failed call becomes a DriveError with the plugin's own text,
// bounded and reduced to printable ASCII, as every string the plugin hands back is.
//
// A plugin runs inside the node's process, with the node's privileges; netmc cannot contain it.
// A crash in it takes the node down: the node is the unit of failure. The drive's own fieldbus
// watchdog then stops the axis, and the server's silence limit ends the job.
//
// A plugin drive runs on its own time (virtual_time() is false): the node positions it between
// iterations. Modes the plugin does not list are refused here, before a call. describe() gives
// the text the plugin gave after create and again after open: any thread may ask for it without
// calling into the plugin, which netmc calls from one thread at a time.

#include <cstdint>
#include <memory>
#include <string>

#include "server/drive/drive.hpp"

extern "C" {
struct netmc_drive_plugin_table;
struct netmc_drive;
}

namespace netmc::drive {

class PluginDrive final : public Drive {
 public:
  // `text` is what follows `plugin:`. Throws std::invalid_argument for anything load() refuses.
  static std::unique_ptr<PluginDrive> load(const std::string& text);
  // Closes the drive if it is still open, destroys it, then unloads the plugin.
  ~PluginDrive() override;

  std::string describe() const override { return description_; }
  OperationMode job_mode() const override { return job_mode_; }

  void open() override;
  void close() noexcept override;
  void write_controlword(std::uint16_t word) override;
  void write_mode(OperationMode mode) override;
  void write_target(OperationMode mode, double value) override;
  DriveFeedback read() override;
  void cycle(double time_s) override;
  void write_quick_stop_deceleration(double deceleration_m_s2) override;

  bool supports(OperationMode mode) const;
  const std::string& path() const { return path_; }

 private:
  struct LibraryCloser {
    void operator()(void* library) const;
  };
  using Library = std::unique_ptr<void, LibraryCloser>;

  PluginDrive(Library library, const netmc_drive_plugin_table* table, netmc_drive* drive, std::string path);
  // The plugin's modes and job mode, checked (std::invalid_argument).
  void query_modes();
  // Asks the plugin what it is (describe) and keeps the answer.
  void refresh_description();
  void require_mode(OperationMode mode, const char* call) const;
  // Throws DriveError naming the call and giving the plugin's text when `status` is a failure.
  void check(int status, const char* call, const char* error) const;

  Library library_;  // first in, last out: the code the other members point into
  const netmc_drive_plugin_table* table_;
  netmc_drive* drive_;
  std::string path_;
  std::string description_;
  std::uint32_t modes_ = 0;  // NETMC_DRIVE_MODE_BIT of each supported mode
  OperationMode job_mode_ = OperationMode::cst;
  bool open_ = false;
};

}  // namespace netmc::drive
