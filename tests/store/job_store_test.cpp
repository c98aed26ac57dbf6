// The job store against SQLite itself: what is written comes back after a reopen, ids are never
// reused, retention deletes what it should and nothing else, schema versions migrate or are
// refused, and a writer killed with SIGKILL at random points leaves a file whose integrity check
// passes and whose accepted jobs are all there.

#include <gtest/gtest.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <random>
#include <string>
#include <thread>

#include "server/store/job_store.hpp"

namespace netmc::store {
namespace {

namespace fs = std::filesystem;

class JobStoreTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() /
                 ("netmc-job-store-" + std::to_string(::getpid()) + "-" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }

  static StoredJob job(const std::string& label, std::uint32_t iterations = 3) {
    StoredJob stored;
    stored.label = label;
    stored.owner = "127.0.0.1:5555";
    stored.spec = "spec of " + label;
    stored.spec.push_back('\0');  // specs are bytes
    stored.spec.append("binary");
    stored.iterations_total = iterations;
    return stored;
  }

  // A statement's single integer answer, through a connection of the test's own.
  std::int64_t query(const std::string& sql) const {
    sqlite3* db = nullptr;
    EXPECT_EQ(sqlite3_open_v2((directory_ / "jobs.sqlite").c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
    sqlite3_stmt* statement = nullptr;
    EXPECT_EQ(sqlite3_prepare_v2(db, sql.c_str(), -1, &statement, nullptr), SQLITE_OK) << sqlite3_errmsg(db);
    std::int64_t value = -1;
    if (sqlite3_step(statement) == SQLITE_ROW) value = sqlite3_column_int64(statement, 0);
    sqlite3_finalize(statement);
    sqlite3_close(db);
    return value;
  }

  std::string integrity() const {
    sqlite3* db = nullptr;
    sqlite3_open_v2((directory_ / "jobs.sqlite").c_str(), &db, SQLITE_OPEN_READWRITE, nullptr);
    sqlite3_stmt* statement = nullptr;
    sqlite3_prepare_v2(db, "PRAGMA integrity_check", -1, &statement, nullptr);
    std::string answer;
    if (sqlite3_step(statement) == SQLITE_ROW) answer = reinterpret_cast<const char*>(sqlite3_column_text(statement, 0));
    sqlite3_finalize(statement);
    sqlite3_close(db);
    return answer;
  }

  fs::path directory_;
};

TEST_F(JobStoreTest, WhatIsWrittenComesBackAfterAReopen) {
  std::uint64_t done_id = 0, running_id = 0, queued_id = 0;
  {
    JobStore store(directory_, {});
    done_id = store.accept(job("done"));
    running_id = store.accept(job("running"));
    queued_id = store.accept(job("queued"));
    EXPECT_LT(done_id, running_id);
    EXPECT_LT(running_id, queued_id);
    store.started(done_id, "header-1");
    store.iteration(done_id, 1, "m1");
    store.ended(done_id, "done", "", "finished-1");
    store.started(running_id, "header-2");
    int told = 0;
    store.iteration(running_id, 1, "m2-1", [&told] { ++told; });
    store.iteration(running_id, 2, "m2-2", [&told] { ++told; });
    store.flush();
    EXPECT_EQ(told, 2);
    EXPECT_EQ(store.problem(), "");
  }
  JobStore reopened(directory_, {});
  const auto contents = reopened.load(100);
  ASSERT_EQ(contents.unfinished.size(), 2u);
  EXPECT_EQ(contents.unfinished[0].id, running_id);
  EXPECT_EQ(contents.unfinished[0].state, "running");
  EXPECT_EQ(contents.unfinished[0].result_header, "header-2");
  ASSERT_EQ(contents.unfinished[0].iterations.size(), 2u);
  EXPECT_EQ(contents.unfinished[0].iterations[1].iteration, 2u);
  EXPECT_EQ(contents.unfinished[0].iterations[1].metrics, "m2-2");
  EXPECT_EQ(contents.unfinished[1].id, queued_id);
  EXPECT_EQ(contents.unfinished[1].state, "queued");
  EXPECT_EQ(contents.unfinished[1].spec, job("queued").spec);  // bytes, embedded NUL included
  EXPECT_EQ(contents.unfinished[1].owner, "127.0.0.1:5555");
  ASSERT_EQ(contents.ended.size(), 1u);
  EXPECT_EQ(contents.ended[0].id, done_id);
  EXPECT_EQ(contents.ended[0].finished, "finished-1");
  EXPECT_EQ(contents.ended[0].iterations_done, 1u);
  EXPECT_GT(contents.ended[0].ended_unix_s, contents.ended[0].accepted_unix_s - 1.0);
  // Every state change has its time and reason.
  EXPECT_EQ(query("SELECT count(*) FROM job_events WHERE job_id = " + std::to_string(done_id)), 3);
  EXPECT_EQ(integrity(), "ok");
}

TEST_F(JobStoreTest, UsesTheWalJournalAndTheCurrentSchema) {
  { JobStore store(directory_, {}); }
  EXPECT_TRUE(fs::exists(directory_ / "jobs.sqlite"));
  EXPECT_EQ(query("PRAGMA user_version"), JobStore::kSchemaVersion);
  sqlite3* db = nullptr;
  sqlite3_open_v2((directory_ / "jobs.sqlite").c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
  sqlite3_stmt* statement = nullptr;
  sqlite3_prepare_v2(db, "PRAGMA journal_mode", -1, &statement, nullptr);
  ASSERT_EQ(sqlite3_step(statement), SQLITE_ROW);
  EXPECT_STREQ(reinterpret_cast<const char*>(sqlite3_column_text(statement, 0)), "wal");
  sqlite3_finalize(statement);
  sqlite3_close(db);
}

TEST_F(JobStoreTest, RefusesAStoreOfANewerSchemaAndNamesTheFile) {
  { JobStore store(directory_, {}); }
  sqlite3* db = nullptr;
  sqlite3_open((directory_ / "jobs.sqlite").c_str(), &db);
  sqlite3_exec(db, "PRAGMA user_version = 99", nullptr, nullptr, nullptr);
  sqlite3_close(db);
  try {
    JobStore store(directory_, {});
    FAIL() << "a newer schema was opened";
  } catch (const StoreError& error) {
    EXPECT_NE(std::string(error.what()).find("jobs.sqlite"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("newer netmc"), std::string::npos) << error.what();
  }
}

TEST_F(JobStoreTest, RefusesAFileThatIsNotADatabase) {
  fs::create_directories(directory_);
  {
    std::FILE* file = std::fopen((directory_ / "jobs.sqlite").c_str(), "w");
    std::fputs("this is not an SQLite database, but long enough to look like a header of one......", file);
    std::fclose(file);
  }
  EXPECT_THROW(JobStore(directory_, {}), StoreError);
}

// One server per store: a second store on the same directory, in this process or another, is
// refused naming the holder's pid; the lock goes with its holder, however that ends.
TEST_F(JobStoreTest, ASecondServerOnTheSameDirectoryIsRefusedNamingTheFirst) {
  {
    JobStore first(directory_, {});
    try {
      JobStore second(directory_, {});
      ADD_FAILURE() << "a second store opened a directory another one owns";
    } catch (const StoreError& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find("another netmc-server (pid " + std::to_string(::getpid()) + ")"), std::string::npos)
          << message;
      EXPECT_NE(message.find("--state-dir"), std::string::npos) << message;
    }
    EXPECT_EQ(first.accept(job("still owned")), 1u);  // the refusal took nothing from the owner
  }
  // Released with its owner; then held by a child that is killed with SIGKILL.
  int ready[2];
  ASSERT_EQ(::pipe(ready), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::close(ready[0]);
    try {
      JobStore owner(directory_, {});
      const char byte = 'y';
      if (::write(ready[1], &byte, 1) != 1) ::_exit(2);
      ::pause();
    } catch (...) {
      ::_exit(1);
    }
    ::_exit(0);
  }
  ::close(ready[1]);
  char byte = 0;
  ASSERT_EQ(::read(ready[0], &byte, 1), 1) << "the child could not take a free store";
  ::close(ready[0]);
  try {
    JobStore refused(directory_, {});
    ADD_FAILURE() << "opened a store another process owns";
  } catch (const StoreError& error) {
    EXPECT_NE(std::string(error.what()).find("(pid " + std::to_string(child) + ")"), std::string::npos) << error.what();
  }
  ::kill(child, SIGKILL);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  JobStore after_kill(directory_, {});
  EXPECT_EQ(after_kill.load(10).ended.size() + after_kill.load(10).unfinished.size(), 1u);
}

// netmc jobs --state-dir: the list a server gives, read from the file with the server running
// (its lock taken) and after it closed; nothing created where there is no store.
TEST_F(JobStoreTest, ReadListsWhatTheOwnerListsWithoutTheOwner) {
  JobFilter all;
  {
    JobStore owner(directory_, {});
    const auto first = owner.accept(job("first"));
    owner.accept(job("second"));
    owner.ended(first, "done", "", "finished");
    owner.flush();
    const auto beside = JobStore::read(directory_, all);
    const auto listed = owner.list(all);
    ASSERT_EQ(beside.size(), 2u);
    ASSERT_EQ(listed.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
      EXPECT_EQ(beside[i].id, listed[i].id);
      EXPECT_EQ(beside[i].state, listed[i].state);
      EXPECT_EQ(beside[i].label, listed[i].label);
    }
    EXPECT_EQ(beside[0].label, "second");  // newest first
  }
  JobFilter done;
  done.state = "done";
  const auto after = JobStore::read(directory_, done);
  ASSERT_EQ(after.size(), 1u);
  EXPECT_EQ(after[0].label, "first");

  const auto nowhere = directory_ / "no-store-here";
  try {
    JobStore::read(nowhere, all);
    ADD_FAILURE() << "read a store that is not there";
  } catch (const StoreError& error) {
    EXPECT_NE(std::string(error.what()).find("jobs.sqlite is missing"), std::string::npos) << error.what();
  }
  EXPECT_FALSE(fs::exists(nowhere));
}

TEST_F(JobStoreTest, ABackupHoldsWhatTheWriteAheadLogHoldsInOneFile) {
  JobFilter all;
  const auto copy_dir = directory_ / "copy";
  const auto plain_dir = directory_ / "plain";
  fs::create_directories(copy_dir);
  fs::create_directories(plain_dir);
  {
    JobStore owner(directory_, {});
    const auto first = owner.accept(job("first"));
    owner.accept(job("second"));
    owner.iteration(first, 1, "metrics 1");
    owner.ended(first, "done", "", "finished");
    owner.flush();
    // While the server owns the store, its newest writes are in jobs.sqlite-wal: a copy of
    // jobs.sqlite alone holds none of them (no checkpoint has run).
    ASSERT_TRUE(fs::exists(directory_ / "jobs.sqlite-wal"));
    fs::copy_file(directory_ / "jobs.sqlite", plain_dir / "jobs.sqlite");
    EXPECT_EQ(query("SELECT COUNT(*) FROM jobs"), 2);  // through SQLite, which reads the log
    EXPECT_EQ(JobStore::backup(directory_, copy_dir / "jobs.sqlite"), 2u);
  }
  // The backup: one file (no log beside it), integrity checked, the same jobs as the store.
  EXPECT_FALSE(fs::exists(copy_dir / "jobs.sqlite-wal"));
  EXPECT_FALSE(fs::exists(copy_dir / "jobs.sqlite.partial"));
  const auto copied = JobStore::read(copy_dir, all);
  const auto original = JobStore::read(directory_, all);
  ASSERT_EQ(copied.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(copied[i].id, original[i].id);
    EXPECT_EQ(copied[i].state, original[i].state);
    EXPECT_EQ(copied[i].label, original[i].label);
  }
  try {
    const auto plain = JobStore::read(plain_dir, all);
    EXPECT_LT(plain.size(), 2u);  // what a copy of the file alone misses
  } catch (const StoreError&) {
    // or not even the schema: the log held that too
  }
  // Refused, naming the flag: no store, no directory for the file, the store itself.
  const auto refused = [&](const fs::path& dir, const fs::path& file, const std::string& expected) {
    try {
      JobStore::backup(dir, file);
      ADD_FAILURE() << "backed up " << dir << " to " << file;
    } catch (const StoreError& error) {
      EXPECT_NE(std::string(error.what()).find(expected), std::string::npos) << error.what();
    }
  };
  refused(directory_ / "none", copy_dir / "x.sqlite", "no job store there");
  refused(directory_, directory_ / "missing" / "x.sqlite", "does not exist");
  refused(directory_, directory_ / "jobs.sqlite", "that is the store itself");
}

TEST_F(JobStoreTest, IdsAreNeverReusedAfterRetentionDeletes) {
  Retention keep_two;
  keep_two.keep_jobs = 2;
  std::vector<std::uint64_t> ids;
  {
    JobStore store(directory_, keep_two);
    for (int n = 0; n < 5; ++n) {
      std::string label = "j";
      label += std::to_string(n);
      ids.push_back(store.accept(job(label)));
      store.ended(ids.back(), "done", "", "f");
    }
    store.flush();
  }
  // The newest two ended jobs stay, with their iterations and events; the rest are gone.
  EXPECT_EQ(query("SELECT count(*) FROM jobs"), 2);
  EXPECT_EQ(query("SELECT min(id) FROM jobs"), static_cast<std::int64_t>(ids[3]));
  EXPECT_EQ(query("SELECT count(*) FROM job_events WHERE job_id < " + std::to_string(ids[3])), 0);
  JobStore reopened(directory_, keep_two);
  EXPECT_GT(reopened.accept(job("next")), ids.back());
}

TEST_F(JobStoreTest, RetentionByAgeKeepsUnfinishedJobs) {
  Retention short_lived;
  short_lived.keep_for = std::chrono::seconds(1);
  JobStore store(directory_, short_lived);
  const auto ended = store.accept(job("ended"));
  const auto queued = store.accept(job("queued"));
  store.ended(ended, "failed", "why", "f");
  store.flush();
  EXPECT_EQ(query("SELECT count(*) FROM jobs"), 2);
  std::this_thread::sleep_for(std::chrono::milliseconds(1200));
  const auto later = store.accept(job("later"));
  store.ended(later, "done", "", "f");  // pruning runs after each end
  store.flush();
  EXPECT_EQ(query("SELECT count(*) FROM jobs WHERE id = " + std::to_string(ended)), 0);
  EXPECT_EQ(query("SELECT count(*) FROM jobs WHERE id = " + std::to_string(queued)), 1);
  EXPECT_EQ(query("SELECT count(*) FROM jobs WHERE id = " + std::to_string(later)), 1);
}

TEST_F(JobStoreTest, ListsNewestFirstWithFilters) {
  JobStore store(directory_, {});
  const auto a = store.accept(job("seed001 adrc"));
  const auto b = store.accept(job("seed002 mfac"));
  const auto c = store.accept(job("seed001 pid"));
  store.ended(a, "done", "", "f");
  store.ended(b, "failed", "axis x silent", "f");
  store.flush();
  const auto all = store.list({});
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0].id, c);
  EXPECT_EQ(all[2].id, a);
  JobFilter failed;
  failed.state = "failed";
  const auto failures = store.list(failed);
  ASSERT_EQ(failures.size(), 1u);
  EXPECT_EQ(failures[0].error, "axis x silent");
  JobFilter seed001;
  seed001.label_contains = "seed001";
  seed001.limit = 1;
  const auto newest = store.list(seed001);
  ASSERT_EQ(newest.size(), 1u);
  EXPECT_EQ(newest[0].id, c);
  JobFilter future;
  future.since_unix_s = 4e9;  // the year 2096
  EXPECT_TRUE(store.list(future).empty());
  // A label with SQL in it is a label.
  JobFilter injection;
  injection.label_contains = "' OR 1=1 --";
  EXPECT_TRUE(store.list(injection).empty());
}

TEST_F(JobStoreTest, AFullWriteQueueDropsWritesButStillTellsTheirFollowers) {
  JobStore store(directory_, {}, 1);
  const auto id = store.accept(job("busy"));
  int told = 0;
  // The writer may take each one at once; at most one waits: some are dropped when it lags.
  for (int n = 0; n < 200; ++n) store.iteration(id, static_cast<std::uint32_t>(n + 1), std::string(1000, 'm'), [&told] { ++told; });
  store.flush();
  EXPECT_EQ(told, 200);
  EXPECT_EQ(query("SELECT count(*) FROM iterations") + static_cast<std::int64_t>(store.dropped_writes()), 200);
}

// A child process writes jobs and iterations as fast as it can; the parent kills it with SIGKILL
// at a random moment, 20 times: every job the child saw accepted is in the file, and the file's
// integrity check passes.
TEST_F(JobStoreTest, SurvivesSigkillDuringWrites) {
  std::mt19937 random(20261126);
  std::uniform_int_distribution<int> kill_after_us(2000, 60000);
  const fs::path accepted_log = fs::temp_directory_path() / ("netmc-job-store-accepted-" + std::to_string(::getpid()));
  fs::remove(accepted_log);
  for (int round = 0; round < 20; ++round) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      try {
        JobStore store(directory_, {});
        for (int n = 0;; ++n) {
          const auto id = store.accept(job("round " + std::to_string(round)));
          // Logged only once accepted: the parent's truth of what must survive.
          std::FILE* log = std::fopen(accepted_log.c_str(), "a");
          std::fprintf(log, "%llu\n", static_cast<unsigned long long>(id));
          std::fclose(log);
          store.iteration(id, 1, std::string(4096, 'x'));
          if (n % 3 == 0) store.ended(id, "done", "", std::string(2048, 'f'));
        }
      } catch (...) {
        ::_exit(3);
      }
    }
    std::this_thread::sleep_for(std::chrono::microseconds(kill_after_us(random)));
    ::kill(child, SIGKILL);
    int status = 0;
    ::waitpid(child, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "round " << round << ": the writer ended by itself (status " << status << ")";
    ASSERT_EQ(integrity(), "ok") << "round " << round;
  }
  std::FILE* log = std::fopen(accepted_log.c_str(), "r");
  ASSERT_NE(log, nullptr);
  unsigned long long id = 0;
  int accepted = 0;
  while (std::fscanf(log, "%llu", &id) == 1) {
    ++accepted;
    EXPECT_EQ(query("SELECT count(*) FROM jobs WHERE id = " + std::to_string(id)), 1) << "job " << id << " lost";
  }
  std::fclose(log);
  fs::remove(accepted_log);
  EXPECT_GT(accepted, 20);
  JobStore reopened(directory_, {});
  EXPECT_EQ(reopened.problem(), "");
}

}  // namespace
}  // namespace netmc::store
