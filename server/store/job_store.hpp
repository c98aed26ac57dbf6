#pragma once
// netmc-server's persistent job store: every accepted job with its spec and owner, its state
// changes with times and reasons, each iteration's metrics as it ends and the final result, in
// one SQLite file (WAL journal, synchronous=FULL), so that a crash or restart loses no accepted
// job and no finished iteration.
//
// One writer thread does every write, in the order asked, off the callers' threads: a job's
// control loop only queues (a bounded queue; a full one drops the write and says so) and is told
// nothing of the disk. Only accept() waits for its write: a job is accepted once it is on disk.
// A write that fails (a full disk) is not lost: it stays first in the queue and is tried again,
// with backoff and at each new write, until it lands; what follows it waits, so a job's writes
// land in order and each `then` runs only once its write is kept.
// The store keeps messages as opaque bytes (serialized protobuf): it knows no job semantics.

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "server/store/state_directory_lock.hpp"

struct sqlite3;

namespace netmc::store {

// A store that cannot be opened or written (full disk, read-only file, corrupt file); the message
// names the file and the cause.
class StoreError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct StoredIteration {
  std::uint32_t iteration = 0;
  std::string metrics;  // netmc.v1.IterationMetrics
};

// One job as the store holds it.
struct StoredJob {
  std::uint64_t id = 0;
  std::string label;
  std::string owner;           // who submitted it (the connection's address, "console", ...)
  std::string spec;            // netmc.v1.JobSpec
  std::uint32_t iterations_total = 0;
  bool keep_after_disconnect = false;
  std::string state;           // queued | running | done | failed | cancelled
  std::string error;
  double accepted_unix_s = 0.0;
  double ended_unix_s = 0.0;   // 0 until it ends
  std::string result_header;   // netmc.v1.JobResult without iterations, once it runs
  std::string finished;        // netmc.v1.JobFinished, once it has ended
  std::vector<StoredIteration> iterations;  // loaded for running jobs only
  std::uint32_t iterations_done = 0;
};

// Which jobs `netmc jobs` lists: newest first.
struct JobFilter {
  std::string state;           // "": any
  std::string label_contains;  // "": any
  double since_unix_s = 0.0;   // accepted at or after; 0: any time
  std::uint32_t limit = 50;    // at most (1..10000)
};

struct Retention {
  std::size_t keep_jobs = 10000;  // ended jobs kept, newest; older ones deleted
  std::chrono::seconds keep_for{std::chrono::hours(24 * 90)};  // ended jobs older than this are deleted
};

class JobStore {
 public:
  // Opens (creating it and DIR if needed) DIR/jobs.sqlite; migrates an older schema; refuses a
  // newer one. Throws StoreError naming the file.
  JobStore(const std::filesystem::path& directory, Retention retention, std::size_t max_pending_writes = 65536);
  ~JobStore();  // finishes the queued writes, then closes
  JobStore(const JobStore&) = delete;
  JobStore& operator=(const JobStore&) = delete;

  // The schema this build writes (PRAGMA user_version).
  static constexpr int kSchemaVersion = 1;
  const std::filesystem::path& file() const { return file_; }

  // At start, before anything else: every job not ended (queued or running, in id order) and the
  // newest `history` ended jobs (oldest first), with what a restart needs of each.
  struct Contents {
    std::vector<StoredJob> unfinished;
    std::vector<StoredJob> ended;
  };
  Contents load(std::size_t history);

  // Writes the job and waits until it is on disk; returns its id (never reused). Throws
  // StoreError (disk full, read-only store, no answer within `timeout`): the job is not accepted.
  std::uint64_t accept(const StoredJob& job, std::chrono::milliseconds timeout = std::chrono::seconds(10));

  // Queued writes; each `then` (optional) runs on the writer thread once the write is kept (a
  // failed one is tried again until it is): so a client is told only of what is kept. A job's
  // end is never dropped from a full queue (an iteration may be: its `then` runs at once).
  using Then = std::function<void()>;
  void started(std::uint64_t id, std::string result_header, Then then = {});
  void iteration(std::uint64_t id, std::uint32_t iteration, std::string metrics, Then then = {});
  void ended(std::uint64_t id, const std::string& state, const std::string& error, std::string finished,
             Then then = {});

  // netmc jobs: from a reading connection of its own (the writer is not waited for).
  std::vector<StoredJob> list(const JobFilter& filter);
  // netmc jobs --state-dir: the same list from DIR/jobs.sqlite without a server, read-only (it
  // creates nothing, takes no lock, and works while a server owns the store). Throws StoreError
  // naming the file when there is no store of this schema there.
  static std::vector<StoredJob> read(const std::filesystem::path& directory, const JobFilter& filter);
  // netmc-server --state-dir DIR --backup FILE: a consistent copy of DIR/jobs.sqlite in one file,
  // what the write-ahead log holds included (a copy of jobs.sqlite alone may hold none of the
  // newest jobs), taken by SQLite's online backup from a read-only connection: beside a running
  // server, taking no lock. FILE is written whole (a temporary beside it, then renamed) and checked
  // (PRAGMA integrity_check). Returns the jobs in it. Throws StoreError naming the file.
  static std::size_t backup(const std::filesystem::path& directory, const std::filesystem::path& file);

  // Empty while writes succeed; otherwise why the latest one failed (writes wait to be tried again).
  std::string problem() const;
  // Writes dropped because the queue was full, and failed attempts to write.
  std::uint64_t dropped_writes() const;
  std::uint64_t failed_writes() const;
  // Blocks until every write queued so far is kept. While the store cannot be written it waits at
  // most `patience`, then gives up the writes still waiting (logged; their `then` never runs: no
  // one is told of what was not kept) and returns false.
  bool flush(std::chrono::milliseconds patience = std::chrono::milliseconds::max());

 private:
  struct Write {
    std::function<void(sqlite3*)> apply;
    Then then;
    std::string what;  // for the log: "iteration 3 of job 7"
    // Set for accept(): never tried again; its waiter hears why now.
    std::function<void(const std::string& why)> refuse;
    bool droppable = true;  // false for a job's end: a full queue takes it all the same
  };
  bool enqueue(Write write);
  void write_loop();
  // Under mutex_: the head failed with `failure`; log it once, refuse the accepts waiting.
  void note_failure(const Write& write, const std::string& failure);
  // Under mutex_: the writes still waiting are given up (stopping, or flush's patience is over).
  void give_up(const std::string& why);
  void prune(sqlite3* db);

  std::optional<StateDirectoryLock> lock_;  // this server's, for the store's life
  std::filesystem::path file_;
  Retention retention_;
  std::size_t max_pending_;
  sqlite3* writer_db_ = nullptr;
  sqlite3* reader_db_ = nullptr;
  std::mutex reader_mutex_;

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable idle_;
  std::deque<Write> pending_;
  bool busy_ = false;
  bool stopping_ = false;
  std::string problem_;
  std::uint64_t dropped_ = 0;
  std::uint64_t failed_ = 0;
  bool failing_ = false;      // the head of the queue failed and waits to be tried again
  bool retry_now_ = false;    // a new write came: try the head again without waiting
  bool giving_up_ = false;    // flush's patience is over: a failing head is given up
  std::chrono::steady_clock::time_point failing_since_;
  std::uint64_t attempts_failed_in_a_row_ = 0;
  std::thread writer_;
};

}  // namespace netmc::store
