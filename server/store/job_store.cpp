#include "server/store/job_store.hpp"

#include <spdlog/spdlog.h>
#include <sqlite3.h>
#include <unistd.h>

#include <cerrno>

#include <algorithm>
#include <atomic>
#include <future>
#include <system_error>
#include <utility>

namespace netmc::store {
namespace {

double unix_now_s() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

// A prepared statement, finalized when it goes out of scope.
class Statement {
 public:
  Statement(sqlite3* db, const char* sql) : db_(db) {
    if (sqlite3_prepare_v2(db, sql, -1, &statement_, nullptr) != SQLITE_OK) fail("prepare");
  }
  ~Statement() { sqlite3_finalize(statement_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  Statement& bind(int index, std::int64_t value) {
    check(sqlite3_bind_int64(statement_, index, value));
    return *this;
  }
  Statement& bind(int index, double value) {
    check(sqlite3_bind_double(statement_, index, value));
    return *this;
  }
  Statement& bind(int index, const std::string& value) {
    check(sqlite3_bind_blob(statement_, index, value.data(), static_cast<int>(value.size()), SQLITE_TRANSIENT));
    return *this;
  }
  Statement& bind_text(int index, const std::string& value) {
    check(sqlite3_bind_text(statement_, index, value.data(), static_cast<int>(value.size()), SQLITE_TRANSIENT));
    return *this;
  }
  // True while there is a row; throws on an error.
  bool step() {
    const int code = sqlite3_step(statement_);
    if (code == SQLITE_ROW) return true;
    if (code == SQLITE_DONE) return false;
    fail("step");
    return false;
  }
  void run() {
    while (step()) {
    }
  }
  std::int64_t integer(int column) const { return sqlite3_column_int64(statement_, column); }
  double real(int column) const { return sqlite3_column_double(statement_, column); }
  std::string bytes(int column) const {
    const auto* data = static_cast<const char*>(sqlite3_column_blob(statement_, column));
    return data ? std::string(data, static_cast<std::size_t>(sqlite3_column_bytes(statement_, column))) : std::string();
  }

 private:
  void check(int code) {
    if (code != SQLITE_OK) fail("bind");
  }
  [[noreturn]] void fail(const char* what) const {
    throw StoreError(std::string(what) + ": " + sqlite3_errmsg(db_));
  }
  sqlite3* db_;
  sqlite3_stmt* statement_ = nullptr;
};

void execute(sqlite3* db, const char* sql) {
  char* message = nullptr;
  if (sqlite3_exec(db, sql, nullptr, nullptr, &message) != SQLITE_OK) {
    std::string text = message ? message : sqlite3_errmsg(db);
    sqlite3_free(message);
    throw StoreError(text);
  }
}

// Schema migrations: entry k takes a store of version k to version k + 1.
constexpr const char* kMigrations[] = {
    // 0 -> 1: jobs, their state changes and their iterations.
    "CREATE TABLE jobs("
    "  id INTEGER PRIMARY KEY AUTOINCREMENT,"
    "  label TEXT NOT NULL, owner TEXT NOT NULL, spec BLOB NOT NULL,"
    "  iterations_total INTEGER NOT NULL, keep_after_disconnect INTEGER NOT NULL,"
    "  state TEXT NOT NULL, error TEXT NOT NULL DEFAULT '',"
    "  accepted_unix_s REAL NOT NULL, ended_unix_s REAL NOT NULL DEFAULT 0,"
    "  result_header BLOB, finished BLOB);"
    "CREATE INDEX jobs_by_state ON jobs(state);"
    "CREATE TABLE job_events(job_id INTEGER NOT NULL, at_unix_s REAL NOT NULL, state TEXT NOT NULL,"
    "  reason TEXT NOT NULL);"
    "CREATE INDEX job_events_by_job ON job_events(job_id);"
    "CREATE TABLE iterations(job_id INTEGER NOT NULL, iteration INTEGER NOT NULL, metrics BLOB NOT NULL,"
    "  PRIMARY KEY(job_id, iteration));",
};
static_assert(std::size(kMigrations) == JobStore::kSchemaVersion);

// The schema version a store was written with (PRAGMA user_version; 0 for a new file).
int schema_version(sqlite3* db) {
  Statement query(db, "PRAGMA user_version");
  query.step();
  return static_cast<int>(query.integer(0));
}

sqlite3* open_database(const std::filesystem::path& file, int flags) {
  sqlite3* db = nullptr;
  const int code = sqlite3_open_v2(file.c_str(), &db, flags | SQLITE_OPEN_FULLMUTEX, nullptr);
  if (code != SQLITE_OK) {
    const std::string message = db ? sqlite3_errmsg(db) : sqlite3_errstr(code);
    sqlite3_close(db);
    throw StoreError("job store " + file.string() + ": cannot open: " + message);
  }
  sqlite3_busy_timeout(db, 5000);
  sqlite3_extended_result_codes(db, 1);
  return db;
}

void add_event(sqlite3* db, std::uint64_t id, const std::string& state, const std::string& reason) {
  Statement(db, "INSERT INTO job_events(job_id, at_unix_s, state, reason) VALUES(?, ?, ?, ?)")
      .bind(1, static_cast<std::int64_t>(id))
      .bind(2, unix_now_s())
      .bind_text(3, state)
      .bind_text(4, reason)
      .run();
}

// A transaction that rolls back unless committed.
class Transaction {
 public:
  explicit Transaction(sqlite3* db) : db_(db) { execute(db_, "BEGIN IMMEDIATE"); }
  ~Transaction() {
    if (!done_) sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
  }
  void commit() {
    execute(db_, "COMMIT");
    done_ = true;
  }

 private:
  sqlite3* db_;
  bool done_ = false;
};

StoredJob read_job_columns(const Statement& row) {
  // id, label, owner, spec, iterations_total, keep, state, error, accepted, ended, header, finished, done
  StoredJob job;
  job.id = static_cast<std::uint64_t>(row.integer(0));
  job.label = row.bytes(1);
  job.owner = row.bytes(2);
  job.spec = row.bytes(3);
  job.iterations_total = static_cast<std::uint32_t>(row.integer(4));
  job.keep_after_disconnect = row.integer(5) != 0;
  job.state = row.bytes(6);
  job.error = row.bytes(7);
  job.accepted_unix_s = row.real(8);
  job.ended_unix_s = row.real(9);
  job.result_header = row.bytes(10);
  job.finished = row.bytes(11);
  job.iterations_done = static_cast<std::uint32_t>(row.integer(12));
  return job;
}

// The columns read_job_columns() takes; the blobs a reader does not need are not read at all
// (a spec may be megabytes, and netmc jobs lists up to 10 000).
std::string job_columns(bool with_spec, bool with_result) {
  return std::string("id, label, owner, ") + (with_spec ? "spec" : "NULL") +
         ", iterations_total, keep_after_disconnect, state, error, accepted_unix_s, ended_unix_s, " +
         (with_result ? "result_header, finished" : "NULL, NULL") +
         ", (SELECT count(*) FROM iterations WHERE job_id = jobs.id)";
}

}  // namespace

JobStore::JobStore(const std::filesystem::path& directory, Retention retention, std::size_t max_pending_writes)
    : file_(directory / "jobs.sqlite"), retention_(retention), max_pending_(max_pending_writes) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) throw StoreError("--state-dir: cannot create " + directory.string() + ": " + error.message());
  // SQLite would open a read-only store and fail at its first write with a vaguer message.
  if (::access(directory.c_str(), W_OK) != 0) {
    throw StoreError("job store " + file_.string() + ": its directory is not writable (" +
                     std::system_category().message(errno) + "): the server could accept no job");
  }
  lock_.emplace(directory);
  writer_db_ = open_database(file_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE);
  try {
    {
      Statement integrity(writer_db_, "PRAGMA quick_check");
      if (integrity.step() && integrity.bytes(0) != "ok") {
        throw StoreError("integrity check failed: " + integrity.bytes(0));
      }
    }
    // WAL: readers (netmc jobs) never wait for the writer; FULL: a committed change survives a
    // power cut, not only a crash of the process.
    {
      Statement journal(writer_db_, "PRAGMA journal_mode=WAL");
      if (!journal.step() || journal.bytes(0) != "wal") throw StoreError("cannot use the WAL journal");
    }
    execute(writer_db_, "PRAGMA synchronous=FULL");
    const int version = schema_version(writer_db_);
    if (version > kSchemaVersion) {
      throw StoreError("schema version " + std::to_string(version) + " was written by a newer netmc (this one knows " +
                       std::to_string(kSchemaVersion) + "); use that netmc, or another --state-dir");
    }
    for (int step = version; step < kSchemaVersion; ++step) {
      Transaction migration(writer_db_);
      execute(writer_db_, kMigrations[step]);
      execute(writer_db_, ("PRAGMA user_version=" + std::to_string(step + 1)).c_str());
      migration.commit();
    }
    try {
      prune(writer_db_);
    } catch (const StoreError& problem) {  // a full disk: the jobs are still there to run
      spdlog::warn("job store {}: old jobs not deleted: {}", file_.string(), problem.what());
    }
    reader_db_ = open_database(file_, SQLITE_OPEN_READONLY);
  } catch (const StoreError& problem) {
    sqlite3_close(writer_db_);
    sqlite3_close(reader_db_);
    throw StoreError("job store " + file_.string() + ": " + problem.what());
  }
  writer_ = std::thread([this] { write_loop(); });
}

JobStore::~JobStore() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  writer_.join();
  sqlite3_close(reader_db_);
  sqlite3_close(writer_db_);
}

JobStore::Contents JobStore::load(std::size_t history) {
  std::lock_guard lock(reader_mutex_);
  Contents contents;
  Statement unfinished(reader_db_, ("SELECT " + job_columns(true, true) + " FROM jobs WHERE state IN ('queued', 'running') ORDER BY id").c_str());
  while (unfinished.step()) contents.unfinished.push_back(read_job_columns(unfinished));
  for (auto& job : contents.unfinished) {
    Statement iterations(reader_db_, "SELECT iteration, metrics FROM iterations WHERE job_id = ? ORDER BY iteration");
    iterations.bind(1, static_cast<std::int64_t>(job.id));
    while (iterations.step()) {
      job.iterations.push_back({static_cast<std::uint32_t>(iterations.integer(0)), iterations.bytes(1)});
    }
  }
  // An ended job needs no spec in memory.
  Statement ended(reader_db_, ("SELECT * FROM (SELECT " + job_columns(false, true) +
                               " FROM jobs WHERE state NOT IN ('queued', 'running') ORDER BY id DESC LIMIT ?) ORDER BY id")
                                  .c_str());
  ended.bind(1, static_cast<std::int64_t>(history));
  while (ended.step()) contents.ended.push_back(read_job_columns(ended));
  return contents;
}

std::uint64_t JobStore::accept(const StoredJob& job, std::chrono::milliseconds timeout) {
  auto outcome = std::make_shared<std::promise<std::uint64_t>>();
  auto result = outcome->get_future();
  // Set when the caller gave up waiting: the client heard "not accepted", so it must not be written.
  auto abandoned = std::make_shared<std::atomic<bool>>(false);
  Write write;
  write.what = "a new job (" + job.label + ")";
  write.apply = [job, outcome, abandoned](sqlite3* db) {
    if (abandoned->load()) {
      outcome->set_exception(std::make_exception_ptr(StoreError("abandoned")));
      return;
    }
    Transaction transaction(db);
    Statement(db,
              "INSERT INTO jobs(label, owner, spec, iterations_total, keep_after_disconnect, state, accepted_unix_s) "
              "VALUES(?, ?, ?, ?, ?, 'queued', ?)")
        .bind_text(1, job.label)
        .bind_text(2, job.owner)
        .bind(3, job.spec)
        .bind(4, static_cast<std::int64_t>(job.iterations_total))
        .bind(5, static_cast<std::int64_t>(job.keep_after_disconnect ? 1 : 0))
        .bind(6, unix_now_s())
        .run();
    const auto id = static_cast<std::uint64_t>(sqlite3_last_insert_rowid(db));
    add_event(db, id, "queued", "accepted from " + job.owner);
    transaction.commit();
    outcome->set_value(id);
  };
  // Not tried again: the client waits for its answer, and a store that cannot be written accepts no job.
  write.refuse = [outcome](const std::string& why) { outcome->set_exception(std::make_exception_ptr(StoreError(why))); };
  if (!enqueue(std::move(write))) {
    throw StoreError("job store " + file_.string() + ": too many writes waiting (" + std::to_string(max_pending_) +
                     "); the disk is too slow or stuck");
  }
  if (result.wait_for(timeout) != std::future_status::ready) {
    abandoned->store(true);
    throw StoreError("job store " + file_.string() + ": the job was not written within " +
                     std::to_string(timeout.count()) + " ms (the disk is too slow or stuck)");
  }
  try {
    return result.get();
  } catch (const std::exception& problem) {
    throw StoreError("job store " + file_.string() + ": " + problem.what());
  }
}

void JobStore::started(std::uint64_t id, std::string result_header, Then then) {
  Write write;
  write.what = "the start of job " + std::to_string(id);
  write.then = std::move(then);
  write.apply = [id, header = std::move(result_header)](sqlite3* db) {
    Transaction transaction(db);
    Statement(db, "UPDATE jobs SET state = 'running', result_header = ? WHERE id = ?")
        .bind(1, header)
        .bind(2, static_cast<std::int64_t>(id))
        .run();
    add_event(db, id, "running", "");
    transaction.commit();
  };
  enqueue(std::move(write));
}

void JobStore::iteration(std::uint64_t id, std::uint32_t iteration, std::string metrics, Then then) {
  Write write;
  write.what = "iteration " + std::to_string(iteration) + " of job " + std::to_string(id);
  write.then = std::move(then);
  write.apply = [id, iteration, metrics = std::move(metrics)](sqlite3* db) {
    Statement(db, "INSERT OR REPLACE INTO iterations(job_id, iteration, metrics) VALUES(?, ?, ?)")
        .bind(1, static_cast<std::int64_t>(id))
        .bind(2, static_cast<std::int64_t>(iteration))
        .bind(3, metrics)
        .run();
  };
  enqueue(std::move(write));
}

void JobStore::ended(std::uint64_t id, const std::string& state, const std::string& error, std::string finished,
                     Then then) {
  Write write;
  write.what = "the end of job " + std::to_string(id);
  write.then = std::move(then);
  write.droppable = false;  // at most one per job, and no job is accepted while writes wait
  write.apply = [this, id, state, error, finished = std::move(finished)](sqlite3* db) {
    {
      Transaction transaction(db);
      Statement(db, "UPDATE jobs SET state = ?, error = ?, ended_unix_s = ?, finished = ? WHERE id = ?")
          .bind_text(1, state)
          .bind_text(2, error)
          .bind(3, unix_now_s())
          .bind(4, finished)
          .bind(5, static_cast<std::int64_t>(id))
          .run();
      add_event(db, id, state, error);
      transaction.commit();
    }
    // The end is kept; retention failing (a full disk) must not write it again.
    try {
      prune(db);
    } catch (const std::exception& problem) {
      spdlog::warn("job store {}: old jobs not deleted: {} (tried again after the next end)", file_.string(),
                   problem.what());
    }
  };
  enqueue(std::move(write));
}

namespace {

std::vector<StoredJob> list_jobs(sqlite3* db, const JobFilter& filter) {
  Statement query(db, ("SELECT " + job_columns(false, false) +
                       " FROM jobs WHERE (?1 = '' OR state = ?1) AND (?2 = '' OR instr(label, ?2) > 0)"
                       " AND accepted_unix_s >= ?3 ORDER BY id DESC LIMIT ?4")
                          .c_str());
  query.bind_text(1, filter.state).bind_text(2, filter.label_contains).bind(3, filter.since_unix_s);
  query.bind(4, static_cast<std::int64_t>(filter.limit));
  std::vector<StoredJob> jobs;
  while (query.step()) jobs.push_back(read_job_columns(query));
  return jobs;
}

}  // namespace

std::vector<StoredJob> JobStore::list(const JobFilter& filter) {
  std::lock_guard lock(reader_mutex_);
  return list_jobs(reader_db_, filter);
}

std::vector<StoredJob> JobStore::read(const std::filesystem::path& directory, const JobFilter& filter) {
  const auto file = directory / "jobs.sqlite";
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error)) {
    throw StoreError("--state-dir " + directory.string() + ": no job store there (" + file.string() +
                     " is missing): name the directory netmc-server's --state-dir names");
  }
  // Read-only, beside a server that may be writing (WAL: readers never wait for the writer), and
  // taking no lock: a store that a server owns can still be read.
  sqlite3* db = open_database(file, SQLITE_OPEN_READONLY);
  try {
    const int version = schema_version(db);
    if (version != kSchemaVersion) {
      throw StoreError("schema version " + std::to_string(version) + ", this netmc reads " +
                       std::to_string(kSchemaVersion) + (version > kSchemaVersion ? ": use a newer netmc" : ""));
    }
    auto jobs = list_jobs(db, filter);
    sqlite3_close(db);
    return jobs;
  } catch (const StoreError& problem) {
    sqlite3_close(db);
    throw StoreError("job store " + file.string() + ": " + problem.what());
  }
}

std::size_t JobStore::backup(const std::filesystem::path& directory, const std::filesystem::path& file) {
  const auto source_file = directory / "jobs.sqlite";
  std::error_code error;
  if (!std::filesystem::is_regular_file(source_file, error)) {
    throw StoreError("--state-dir " + directory.string() + ": no job store there (" + source_file.string() +
                     " is missing)");
  }
  const auto parent = file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
  if (!std::filesystem::is_directory(parent, error)) {
    throw StoreError("--backup " + file.string() + ": directory " + parent.string() + " does not exist");
  }
  if (std::filesystem::exists(file, error) && std::filesystem::equivalent(file, source_file, error)) {
    throw StoreError("--backup " + file.string() + ": that is the store itself");
  }
  const auto temporary = std::filesystem::path(file.string() + ".partial");
  std::filesystem::remove(temporary, error);
  sqlite3* source = open_database(source_file, SQLITE_OPEN_READONLY);
  sqlite3* target = nullptr;
  const auto fail = [&](const std::string& why) {
    sqlite3_close(target);
    sqlite3_close(source);
    std::filesystem::remove(temporary, error);
    return StoreError("--backup " + file.string() + ": " + why);
  };
  try {
    if (schema_version(source) != kSchemaVersion) throw StoreError("the store's schema is not this netmc's");
    target = open_database(temporary, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE);
  } catch (const StoreError& problem) {
    throw fail(problem.what());
  }
  // The whole database in one step: a writer's commit meanwhile restarts it, so it is one state.
  sqlite3_backup* copy = sqlite3_backup_init(target, "main", source, "main");
  if (!copy) throw fail(sqlite3_errmsg(target));
  int code = SQLITE_OK;
  for (int attempt = 0; attempt < 100; ++attempt) {
    code = sqlite3_backup_step(copy, -1);
    if (code != SQLITE_BUSY && code != SQLITE_LOCKED) break;
    sqlite3_sleep(50);
  }
  sqlite3_backup_finish(copy);
  if (code != SQLITE_DONE) throw fail(std::string("the copy failed: ") + sqlite3_errstr(code));
  std::size_t jobs = 0;
  try {
    // The copy is a database in one file (no write-ahead log of its own to lose).
    execute(target, "PRAGMA journal_mode=DELETE");
    Statement integrity(target, "PRAGMA integrity_check");
    if (!integrity.step() || integrity.bytes(0) != "ok") throw StoreError("the copy fails its integrity check");
    Statement count(target, "SELECT COUNT(*) FROM jobs");
    count.step();
    jobs = static_cast<std::size_t>(count.integer(0));
  } catch (const StoreError& problem) {
    throw fail(problem.what());
  }
  sqlite3_close(target);
  sqlite3_close(source);
  std::filesystem::rename(temporary, file, error);
  if (error) {
    std::filesystem::remove(temporary, error);
    throw StoreError("--backup " + file.string() + ": cannot rename the copy into place: " + error.message());
  }
  return jobs;
}

std::string JobStore::problem() const {
  std::lock_guard lock(mutex_);
  return problem_;
}

std::uint64_t JobStore::dropped_writes() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}

std::uint64_t JobStore::failed_writes() const {
  std::lock_guard lock(mutex_);
  return failed_;
}

bool JobStore::flush(std::chrono::milliseconds patience) {
  std::unique_lock lock(mutex_);
  const auto idle = [this] { return pending_.empty() && !busy_; };
  const bool forever = patience == std::chrono::milliseconds::max();
  const auto deadline = forever ? std::chrono::steady_clock::time_point::max() : std::chrono::steady_clock::now() + patience;
  while (!idle()) {
    if (!failing_ || forever) {
      // A slow disk is waited for; a failing one only until the patience is over.
      idle_.wait(lock, [&] { return idle() || (failing_ && !forever); });
      continue;
    }
    if (idle_.wait_until(lock, deadline, idle)) break;
    if (!failing_) continue;  // written again, but not all yet
    giving_up_ = true;
    give_up("not kept within " + std::to_string(patience.count()) + " ms");
    wake_.notify_all();
    // The attempt under way ends, given up too if it fails.
    idle_.wait(lock, [this] { return !busy_; });
    giving_up_ = false;
    return false;
  }
  return true;
}

bool JobStore::enqueue(Write write) {
  {
    std::lock_guard lock(mutex_);
    if (pending_.size() < max_pending_ || !write.droppable) {
      pending_.push_back(std::move(write));
      retry_now_ = true;  // a write failing at the head is tried again now
      wake_.notify_one();
      return true;
    }
    ++dropped_;
    const std::string dropped = "too many writes waiting (" + std::to_string(max_pending_) + "): " + write.what + " was dropped";
    if (!failing_) problem_ = dropped;
    // The first of a run of drops, then every thousandth: a stuck disk must not also flood the log.
    if (dropped_ % 1000 == 1) spdlog::error("job store {}: {} ({} dropped so far)", file_.string(), dropped, dropped_);
  }
  // Dropped: its follower still runs, so no client waits for a write that never comes.
  if (write.then) write.then();
  return false;
}

namespace {
// A failed write is tried again after these, doubling (and at once when a new write comes).
constexpr std::chrono::milliseconds kFirstRetry{100};
constexpr std::chrono::milliseconds kLongestRetry{2000};
}  // namespace

void JobStore::write_loop() {
  std::unique_lock lock(mutex_);
  std::chrono::milliseconds backoff = kFirstRetry;
  while (true) {
    wake_.wait(lock, [this] { return stopping_ || !pending_.empty(); });
    if (pending_.empty()) return;  // stopping, every queued write done
    Write write = std::move(pending_.front());
    pending_.pop_front();
    busy_ = true;
    retry_now_ = false;
    lock.unlock();
    std::string failure;
    try {
      write.apply(writer_db_);
    } catch (const std::exception& problem) {
      failure = problem.what();
    }
    lock.lock();
    if (failure.empty()) {
      if (failing_) {
        spdlog::info("job store {}: written again after {:.1f} s ({} failed attempts); {} writes waiting", file_.string(),
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - failing_since_).count(),
                     attempts_failed_in_a_row_, pending_.size());
        failing_ = false;
        attempts_failed_in_a_row_ = 0;
        backoff = kFirstRetry;
      }
      problem_.clear();
      lock.unlock();
      if (write.then) write.then();
      lock.lock();
      busy_ = false;
      if (pending_.empty()) idle_.notify_all();
      continue;
    }
    ++failed_;
    note_failure(write, failure);
    if (write.refuse) {
      write.refuse(failure);
    } else {
      pending_.push_front(std::move(write));  // first again: what follows it waits, in order
    }
    busy_ = false;
    if (stopping_ || giving_up_) give_up(stopping_ ? "the store closes" : "flush gave up");
    idle_.notify_all();
    if (stopping_ || giving_up_) continue;
    wake_.wait_for(lock, backoff, [this] { return stopping_ || giving_up_ || retry_now_; });
    backoff = std::min(backoff * 2, kLongestRetry);
  }
}

void JobStore::note_failure(const Write& write, const std::string& failure) {
  const std::size_t waiting = pending_.size() + 1;  // with this one, when it is tried again
  // Each failure once (again only when its cause changes), and its recovery: not every attempt.
  if (write.refuse && (!failing_ || failure != problem_)) {
    spdlog::error("job store {}: {} not accepted: {}", file_.string(), write.what, failure);
  } else if (!failing_ || failure != problem_) {
    spdlog::error("job store {}: {} not written: {}; {} writes wait and are tried again until they are kept (no job "
                  "is accepted meanwhile)",
                  file_.string(), write.what, failure, waiting);
  }
  if (!failing_) failing_since_ = std::chrono::steady_clock::now();
  failing_ = true;
  problem_ = failure;
  ++attempts_failed_in_a_row_;
  // New jobs behind the failing write: their clients hear why now, not after accept's timeout.
  for (auto it = pending_.begin(); it != pending_.end();) {
    if (it->refuse) {
      it->refuse(failure);
      it = pending_.erase(it);
    } else {
      ++it;
    }
  }
}

void JobStore::give_up(const std::string& why) {
  if (pending_.empty()) return;
  spdlog::error("job store {}: {} writes given up ({}): {}; no one was told of them, and their jobs read as the store "
                "last kept them (a running one: 'server restarted' at the next start)",
                file_.string(), pending_.size(), why, problem_.empty() ? "not written" : problem_);
  for (auto& write : pending_) {
    if (write.refuse) write.refuse(problem_.empty() ? why : problem_);
  }
  dropped_ += pending_.size();
  pending_.clear();
}

void JobStore::prune(sqlite3* db) {
  // Ended jobs beyond the newest keep_jobs, or ended longer ago than keep_for.
  const double oldest = unix_now_s() - std::chrono::duration<double>(retention_.keep_for).count();
  Transaction transaction(db);
  Statement(db,
            "CREATE TEMP TABLE IF NOT EXISTS doomed(id INTEGER PRIMARY KEY);")
      .run();
  execute(db, "DELETE FROM temp.doomed");
  Statement(db,
            "INSERT OR IGNORE INTO temp.doomed SELECT id FROM jobs WHERE state NOT IN ('queued', 'running') AND "
            "(ended_unix_s < ?1 OR id NOT IN (SELECT id FROM jobs WHERE state NOT IN ('queued', 'running') "
            "ORDER BY id DESC LIMIT ?2))")
      .bind(1, oldest)
      .bind(2, static_cast<std::int64_t>(retention_.keep_jobs))
      .run();
  execute(db, "DELETE FROM iterations WHERE job_id IN (SELECT id FROM temp.doomed);"
              "DELETE FROM job_events WHERE job_id IN (SELECT id FROM temp.doomed);"
              "DELETE FROM jobs WHERE id IN (SELECT id FROM temp.doomed);");
  transaction.commit();
}

}  // namespace netmc::store
