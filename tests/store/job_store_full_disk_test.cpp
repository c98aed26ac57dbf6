// The job store on a disk that fills up (tests/store/full_disk.hpp: SQLite's writes fail with
// SQLITE_FULL on demand): a write that fails is tried again until it is kept, in order, and its
// follower runs only then; a new job is refused at once with the reason; a job's end is never
// dropped; flush's patience and the store's close give up what cannot be written, telling no one.

#include <gtest/gtest.h>
#include <sqlite3.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

#include "server/store/job_store.hpp"
#include "tests/store/full_disk.hpp"

namespace netmc::store {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

class JobStoreFullDiskTest : public ::testing::Test {
 protected:
  void SetUp() override { fs::remove_all(directory_); }
  void TearDown() override {
    disk_.make_room();
    fs::remove_all(directory_);
  }

  static StoredJob job(const std::string& label) {
    StoredJob stored;
    stored.label = label;
    stored.owner = "127.0.0.1:5555";
    stored.spec = "spec of " + label;
    stored.iterations_total = 3;
    return stored;
  }

  // What the store holds, read as netmc jobs --state-dir reads it.
  StoredJob read(std::uint64_t id) const {
    for (const auto& row : JobStore::read(directory_, {})) {
      if (row.id == id) return row;
    }
    ADD_FAILURE() << "job " << id << " not in the store";
    return {};
  }

  testing::FullDisk disk_;
  fs::path directory_ = fs::temp_directory_path() / ("netmc-store-full-" + std::to_string(::getpid()) + "-" +
                                                     ::testing::UnitTest::GetInstance()->current_test_info()->name());
};

TEST_F(JobStoreFullDiskTest, AFailedWriteIsKeptOnceThereIsRoomAndOnlyThenIsItsFollowerRun) {
  JobStore store(directory_, {});
  const auto id = store.accept(job("long"));
  store.started(id, "header");
  std::atomic<int> iterations_told{0}, ends_told{0};
  store.iteration(id, 1, "metrics 1", [&] { ++iterations_told; });
  store.flush();
  ASSERT_EQ(iterations_told, 1);

  disk_.fill();
  store.iteration(id, 2, "metrics 2", [&] { ++iterations_told; });
  store.iteration(id, 3, "metrics 3", [&] { ++iterations_told; });
  store.ended(id, "done", "", "finished", [&] { ++ends_told; });
  std::this_thread::sleep_for(500ms);  // a few attempts (0.1, 0.2 s backoff)
  EXPECT_EQ(iterations_told, 1) << "told of iterations that were not kept";
  EXPECT_EQ(ends_told, 0) << "told of an end that was not kept";
  EXPECT_NE(store.problem().find("full"), std::string::npos) << store.problem();
  EXPECT_GE(store.failed_writes(), 2u);
  EXPECT_EQ(read(id).state, "running");
  EXPECT_EQ(read(id).iterations_done, 1u);

  // A new job meanwhile: refused at once, with the reason, not after accept's 10 s.
  const auto asked = Clock::now();
  try {
    store.accept(job("refused"));
    ADD_FAILURE() << "a job was accepted by a store that cannot be written";
  } catch (const StoreError& error) {
    EXPECT_NE(std::string(error.what()).find("jobs.sqlite: "), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("full"), std::string::npos) << error.what();
  }
  EXPECT_LT(Clock::now() - asked, 2s);

  disk_.make_room();
  store.flush();
  EXPECT_EQ(iterations_told, 3);
  EXPECT_EQ(ends_told, 1);
  EXPECT_EQ(store.problem(), "");
  EXPECT_EQ(store.dropped_writes(), 0u);
  const auto kept = read(id);
  EXPECT_EQ(kept.state, "done");
  EXPECT_EQ(kept.iterations_done, 3u);
  EXPECT_EQ(JobStore::read(directory_, {}).size(), 1u) << "the refused job was kept";
}

TEST_F(JobStoreFullDiskTest, ANewWriteTriesTheFailedOneAgainWithoutWaitingForTheBackoff) {
  JobStore store(directory_, {});
  const auto id = store.accept(job("waits"));
  std::atomic<int> told{0};
  disk_.fill();
  store.iteration(id, 1, "metrics 1", [&] { ++told; });
  std::this_thread::sleep_for(2s);  // the backoff has grown to 1.6 s
  disk_.make_room();
  const auto room = Clock::now();
  store.iteration(id, 2, "metrics 2", [&] { ++told; });
  while (told < 2 && Clock::now() - room < 5s) std::this_thread::sleep_for(1ms);
  const auto took = Clock::now() - room;
  EXPECT_EQ(told, 2);
  EXPECT_LT(took, 500ms) << "the new write waited for the backoff";
  std::printf("kept %.1f ms after a new write came (backoff then about 1.6 s)\n",
              std::chrono::duration<double, std::milli>(took).count());
}

TEST_F(JobStoreFullDiskTest, WithRoomAgainTheBackoffAloneKeepsTheWaitingWrites) {
  JobStore store(directory_, {});
  const auto id = store.accept(job("alone"));
  std::atomic<int> told{0};
  disk_.fill();
  store.ended(id, "failed", "its axis stopped", "finished", [&] { ++told; });
  std::this_thread::sleep_for(300ms);
  disk_.make_room();
  const auto room = Clock::now();
  while (told < 1 && Clock::now() - room < 10s) std::this_thread::sleep_for(5ms);
  EXPECT_EQ(told, 1);
  EXPECT_LT(Clock::now() - room, 4s) << "longer than the longest backoff (2 s)";
  EXPECT_EQ(read(id).state, "failed");
  EXPECT_EQ(read(id).error, "its axis stopped");
}

TEST_F(JobStoreFullDiskTest, AJobsEndIsNeverDroppedFromAFullQueue) {
  JobStore store(directory_, {}, 2);
  const auto id = store.accept(job("crowded"));
  disk_.fill();
  std::atomic<int> told{0}, ended{0};
  for (std::uint32_t n = 1; n <= 5; ++n) store.iteration(id, n, "metrics", [&] { ++told; });
  store.ended(id, "done", "", "finished", [&] { ++ended; });
  // The iterations beyond the queue's 2 (3 with the one being tried) were dropped, and their
  // followers run at once.
  EXPECT_GE(store.dropped_writes(), 2u);
  EXPECT_EQ(told, static_cast<int>(store.dropped_writes()));
  EXPECT_EQ(ended, 0);
  disk_.make_room();
  store.flush();
  EXPECT_EQ(ended, 1);
  EXPECT_EQ(read(id).state, "done");
}

TEST_F(JobStoreFullDiskTest, FlushGivesUpAfterItsPatienceAndTellsNoOneOfWhatWasNotKept) {
  std::uint64_t id = 0;
  std::atomic<int> told{0};
  {
    JobStore store(directory_, {});
    id = store.accept(job("stopped"));
    store.started(id, "header");
    store.iteration(id, 1, "metrics 1", [&] { ++told; });
    store.flush();
    disk_.fill();
    store.iteration(id, 2, "metrics 2", [&] { ++told; });
    store.ended(id, "cancelled", "the server is shutting down", "finished", [&] { ++told; });
    const auto asked = Clock::now();
    EXPECT_FALSE(store.flush(300ms));
    EXPECT_LT(Clock::now() - asked, 2s);
    EXPECT_EQ(store.dropped_writes(), 2u);
    store.iteration(id, 3, "metrics 3", [&] { ++told; });  // the close gives this one up too, at once
  }
  EXPECT_EQ(told, 1);
  disk_.make_room();
  const auto kept = read(id);
  EXPECT_EQ(kept.state, "running");  // as last kept: a restart fails it "server restarted during iteration 2"
  EXPECT_EQ(kept.iterations_done, 1u);
}

TEST_F(JobStoreFullDiskTest, AStoreClosedOnAFullDiskDoesNotWaitForRoom) {
  const auto started = Clock::now();
  {
    JobStore store(directory_, {});
    const auto id = store.accept(job("closing"));
    disk_.fill();
    store.ended(id, "done", "", "finished");
    std::this_thread::sleep_for(200ms);
  }
  EXPECT_LT(Clock::now() - started, 3s);
}

}  // namespace
}  // namespace netmc::store
