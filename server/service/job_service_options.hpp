#pragma once
// What netmc-server's job service is configured with (netmc-server's options): its limits,
// timeouts, allowed plugins, live view and store. See docs/architecture.md, Threads and queues.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "server/dds/time_base.hpp"
#include "server/job/job_builder.hpp"
#include "server/sim/cycle_listener.hpp"
#include "server/store/job_store.hpp"

namespace netmc::service {

struct JobServiceOptions {
  std::chrono::milliseconds axis_timeout{2000};       // per lockstep exchange
  std::chrono::milliseconds discovery_timeout{10000}; // waiting for the nodes of a job
  std::chrono::milliseconds silence_limit{500};       // realtime: an axis silent this long fails
  dds::TimeBase time_base = dds::TimeBase::monotonic; // realtime jobs' schedule
  std::size_t max_running_jobs = 32;
  std::size_t max_queued_jobs = 256;                  // waiting for validation or for axes
  std::size_t job_history = 256;                      // ended jobs kept in memory for status and watch
  // Bytes of job specs waiting (for validation or for axes); a submit beyond is refused. A spec
  // may carry inline delay traces of megabytes.
  std::size_t max_queued_spec_bytes = std::size_t{256} << 20;
  std::size_t max_watchers_per_job = 16;              // netmc watch connections following one job
  // Realtime: for every axis to stand ready at an iteration's start (hardware is moved there).
  std::chrono::milliseconds positioning_timeout{60000};
  // An axis held by another server: how long a job waits for the hold to end (a node lets the
  // hold of a server it no longer hears from go after its hold lease, 10 s).
  std::chrono::milliseconds foreign_hold_wait{15000};
  // The server has an admin token: resetting an axis's fault needs it.
  bool admin_token_configured = false;
  // Controller plugins a job may name (netmc-server --allow-plugin), exact paths; none: no plugin.
  std::vector<std::string> allowed_plugins;
  // A live view of each job's cycles (the console): called when a job starts running; null or
  // unset: none.
  std::function<std::shared_ptr<sim::CycleListener>(std::uint64_t job_id)> live_cycles;
  // The persistent job store (netmc-server --state-dir); null: jobs live in memory only. When
  // set, a job is accepted only once it is on disk, a client hears of an iteration only once it
  // is kept, and the service starts with the store's queue and history.
  std::shared_ptr<store::JobStore> store;

  // How the server builds a job: the controller here (a plugin only if allowed), plants read
  // from files only on their axis nodes.
  job::JobBuildOptions build_options() const {
    job::JobBuildOptions build;
    build.load_plant_files = false;
    build.controller_plugins.allowed = allowed_plugins;
    return build;
  }
};

}  // namespace netmc::service
