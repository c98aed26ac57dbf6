// A job's iterations and end on a disk that fills up, in one process (no DDS, no socket): its
// watchers hear only of what the job store kept, the end waits (its status says why) until there
// is room, and after a restart the store's history is what the watchers saw; a server stopped
// while the disk is still full told no one of what it could not keep.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "server/service/job_registry.hpp"
#include "server/store/job_store.hpp"
#include "tests/store/full_disk.hpp"

namespace netmc::service {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

// A watcher's connection: what it was sent.
class Recorder : public management::Peer {
 public:
  void send(const netmc::v1::Response& response) override {
    std::lock_guard lock(mutex_);
    responses_.push_back(response);
  }
  bool open() const override { return true; }
  void hold() override {}
  void release() override {}

  // What `netmc watch` shows: the iterations it was sent and the end, if any.
  struct Seen {
    std::vector<std::uint32_t> iterations;
    std::optional<netmc::v1::JobFinished> end;
  };
  Seen seen() const {
    std::lock_guard lock(mutex_);
    Seen seen;
    for (const auto& response : responses_) {
      if (response.has_iteration()) seen.iterations.push_back(response.iteration().metrics().iteration());
      if (response.has_finished()) seen.end = response.finished();
    }
    return seen;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<netmc::v1::Response> responses_;
};

class JobEndFullDiskTest : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::remove_all(directory_);
    options_.store = std::make_shared<store::JobStore>(directory_, store::Retention{});
  }
  void TearDown() override {
    disk_.make_room();
    fs::remove_all(directory_);
  }

  // A running job of three iterations in `registry` (its id in id_), watched by watcher_, its
  // first iteration kept and told.
  std::shared_ptr<Job> running_job(JobRegistry& registry) {
    store::StoredJob stored;
    stored.label = "full-disk";
    stored.owner = "127.0.0.1:1";
    stored.spec = "spec";
    stored.iterations_total = 3;
    const auto id = id_ = options_.store->accept(stored);
    auto job = std::make_shared<Job>();
    {
      std::lock_guard lock(registry.mutex());
      registry.add(job, id);
      job->status.set_job_id(id);
      job->status.set_state("running");
      job->status.set_iterations_total(3);
      options_.store->started(id, "");
      registry.start_watch(*job, watcher_, 7);
    }
    registry.report_iteration(job, iteration(*job, 1));
    options_.store->flush();
    return job;
  }

  static netmc::v1::Response iteration(const Job& job, std::uint32_t n) {
    netmc::v1::Response update;
    update.mutable_iteration()->set_job_id(job.id);
    update.mutable_iteration()->set_total_iterations(3);
    update.mutable_iteration()->mutable_metrics()->set_iteration(n);
    update.mutable_iteration()->mutable_metrics()->set_e_max_m(1e-5 * n);
    return update;
  }

  static netmc::v1::JobFinished done(const Job& job, std::uint32_t iterations) {
    netmc::v1::JobFinished finished;
    finished.set_job_id(job.id);
    finished.set_state("done");
    for (std::uint32_t n = 1; n <= iterations; ++n) *finished.mutable_result()->add_iterations() = iteration(job, n).iteration().metrics();
    return finished;
  }

  // The server restarts on the store: what its registry and `netmc jobs --state-dir` hold of `id`.
  struct Restarted {
    netmc::v1::JobStatus status;
    int finished_iterations = -1;
    store::StoredJob row;
  };
  Restarted restart(std::uint64_t id) {
    JobServiceOptions options;
    options.store = std::make_shared<store::JobStore>(directory_, store::Retention{});
    JobRegistry registry(options);
    Restarted restarted;
    std::lock_guard lock(registry.mutex());
    registry.restore_from_store();
    const auto job = registry.find(id);
    EXPECT_TRUE(job);
    if (!job) return restarted;
    restarted.status = job->status;
    if (job->finished) restarted.finished_iterations = job->finished->result().iterations_size();
    options.store->flush();
    for (const auto& row : store::JobStore::read(directory_, {})) {
      if (row.id == id) restarted.row = row;
    }
    return restarted;
  }

  store::testing::FullDisk disk_;
  fs::path directory_ = fs::temp_directory_path() / ("netmc-end-full-" + std::to_string(::getpid()) + "-" +
                                                     ::testing::UnitTest::GetInstance()->current_test_info()->name());
  JobServiceOptions options_;
  std::shared_ptr<Recorder> watcher_ = std::make_shared<Recorder>();
  std::uint64_t id_ = 0;
};

TEST_F(JobEndFullDiskTest, AJobThatEndsOnAFullDiskIsToldDoneOnceKeptAndARestartFindsWhatItsWatcherSaw) {
  {
    JobRegistry registry(options_);
    const auto job = running_job(registry);
    EXPECT_EQ(watcher_->seen().iterations, (std::vector<std::uint32_t>{1}));

    disk_.fill();
    registry.report_iteration(job, iteration(*job, 2));
    registry.report_iteration(job, iteration(*job, 3));
    std::this_thread::sleep_for(300ms);  // the store has failed a few times
    registry.conclude(job, done(*job, 3));
    std::this_thread::sleep_for(300ms);
    // Nothing the store did not keep was told; the job's status says what its end waits for.
    EXPECT_EQ(watcher_->seen().iterations, (std::vector<std::uint32_t>{1}));
    EXPECT_FALSE(watcher_->seen().end);
    {
      std::lock_guard lock(registry.mutex());
      EXPECT_EQ(job->status.state(), "running");
      EXPECT_NE(job->status.waiting_for().find("its end (done) to be written to the job store"), std::string::npos)
          << job->status.waiting_for();
      EXPECT_NE(job->status.waiting_for().find("full"), std::string::npos) << job->status.waiting_for();
    }

    disk_.make_room();
    options_.store->flush();
    const auto seen = watcher_->seen();
    EXPECT_EQ(seen.iterations, (std::vector<std::uint32_t>{1, 2, 3}));
    ASSERT_TRUE(seen.end);
    EXPECT_EQ(seen.end->state(), "done");
    std::lock_guard lock(registry.mutex());
    EXPECT_EQ(job->status.state(), "done");
    EXPECT_EQ(job->status.waiting_for(), "");
  }
  options_.store.reset();

  const auto restarted = restart(id_);
  const auto seen = watcher_->seen();
  EXPECT_EQ(restarted.status.state(), seen.end->state());
  EXPECT_EQ(restarted.status.error(), seen.end->error());
  EXPECT_EQ(restarted.finished_iterations, static_cast<int>(seen.iterations.size()));
  EXPECT_EQ(restarted.row.state, "done");
  EXPECT_EQ(restarted.row.error, "");
  EXPECT_EQ(restarted.row.iterations_done, seen.iterations.size());
}

TEST_F(JobEndFullDiskTest, AServerStoppedWhileTheDiskIsFullToldNoOneOfWhatARestartDoesNotFind) {
  {
    JobRegistry registry(options_);
    const auto job = running_job(registry);
    disk_.fill();
    registry.report_iteration(job, iteration(*job, 2));
    registry.conclude(job, done(*job, 2));
    // The server stops (JobService's destructor): the store waits a little, then gives up.
    EXPECT_FALSE(options_.store->flush(300ms));
  }
  options_.store.reset();
  disk_.make_room();

  const auto seen = watcher_->seen();
  EXPECT_EQ(seen.iterations, (std::vector<std::uint32_t>{1}));
  EXPECT_FALSE(seen.end) << "the watcher was told of an end the store never kept";
  // The restart fails the job in the iteration the watcher had not seen, with what it had seen.
  const auto restarted = restart(id_);
  EXPECT_EQ(restarted.status.state(), "failed");
  EXPECT_EQ(restarted.status.error(), "server restarted during iteration 2");
  EXPECT_EQ(restarted.finished_iterations, 1);
  EXPECT_EQ(restarted.row.state, "failed");
  EXPECT_EQ(restarted.row.iterations_done, 1u);
}

}  // namespace
}  // namespace netmc::service
