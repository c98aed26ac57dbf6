// The registry's restart from the job store, in one process (no DDS, no socket): a queued job
// whose stored spec was edited to name a file, to break a field's range or to be unreadable is
// failed with the check's message and no byte of the file; a valid one is queued again; a job
// that was running is failed naming the iteration it was in, with what it finished.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "server/job/presets/presets.hpp"
#include "server/service/job_registry.hpp"
#include "server/store/job_store.hpp"

namespace netmc::service {
namespace {

namespace fs = std::filesystem;

struct Scratch {
  fs::path dir = fs::temp_directory_path() / ("netmc-registry-" + std::to_string(::getpid()) + "-" +
                                              ::testing::UnitTest::GetInstance()->current_test_info()->name());
  Scratch() { fs::remove_all(dir); }
  ~Scratch() { fs::remove_all(dir); }
};

store::StoredJob stored(const netmc::v1::JobSpec& spec, const std::string& label) {
  store::StoredJob job;
  job.label = label;
  job.owner = "127.0.0.1:1";
  job.spec = spec.SerializeAsString();
  job.iterations_total = spec.iterations();
  return job;
}

TEST(JobRegistryRestore, StoredSpecsAreCheckedAsSubmittedOnesAndNoFileTheyNameIsRead) {
  Scratch scratch;
  const fs::path secret = scratch.dir / "secret.txt";
  fs::create_directories(scratch.dir);
  std::ofstream(secret) << "0.001\nTOP-SECRET-LINE\n";
  netmc::v1::JobSpec valid = presets::make_preset("seed001").jobs.front();
  valid.set_iterations(2);
  netmc::v1::JobSpec names_a_file = valid;
  names_a_file.mutable_downlink()->mutable_delay()->mutable_trace()->set_path(secret.string());
  netmc::v1::JobSpec out_of_range = valid;
  out_of_range.set_sample_period_s(-1.0);
  std::uint64_t valid_id = 0, file_id = 0, range_id = 0, unreadable_id = 0, running_id = 0;
  {
    store::JobStore store(scratch.dir / "state", {});
    valid_id = store.accept(stored(valid, "valid"));
    file_id = store.accept(stored(names_a_file, "names a file"));
    range_id = store.accept(stored(out_of_range, "out of range"));
    auto garbage = stored(valid, "unreadable");
    garbage.spec = "\xff\xff\xff not a spec";
    unreadable_id = store.accept(garbage);
    running_id = store.accept(stored(valid, "running"));
    store.started(running_id, "");
    netmc::v1::IterationMetrics first;
    first.set_iteration(1);
    first.set_e_max_m(8.3e-5);
    store.iteration(running_id, 1, first.SerializeAsString());
    store.flush();
  }
  JobServiceOptions options;
  options.store = std::make_shared<store::JobStore>(scratch.dir / "state", store::Retention{});
  JobRegistry registry(options);
  std::vector<std::shared_ptr<Job>> requeued;
  {
    std::lock_guard lock(registry.mutex());
    requeued = registry.restore_from_store();
  }
  ASSERT_EQ(requeued.size(), 1u);
  EXPECT_EQ(requeued.front()->id, valid_id);
  EXPECT_EQ(requeued.front()->axes, (std::vector<std::string>{"x", "y"}));
  const auto status = [&](std::uint64_t id) {
    std::lock_guard lock(registry.mutex());
    const auto job = registry.find(id);
    EXPECT_TRUE(job) << id;
    return job ? job->status : netmc::v1::JobStatus{};
  };
  const auto file = status(file_id);
  EXPECT_EQ(file.state(), "failed");
  EXPECT_EQ(file.error().rfind("its stored spec fails the checks of a submitted one: downlink.delay.trace.path: a job "
                               "from the network names no file",
                               0),
            0u)
      << file.error();
  EXPECT_EQ(file.error().find("TOP-SECRET"), std::string::npos);
  const auto range = status(range_id);
  EXPECT_EQ(range.state(), "failed");
  EXPECT_NE(range.error().find("sample_period: expected a number in [1e-06, 1] s, got -1"), std::string::npos)
      << range.error();
  EXPECT_EQ(status(unreadable_id).error(), "its stored spec cannot be read");
  const auto running = status(running_id);
  EXPECT_EQ(running.state(), "failed");
  EXPECT_EQ(running.error(), "server restarted during iteration 2");
  // What the restart decided is in the store too: a second restart finds the same.
  options.store->flush();
  const auto listed = store::JobStore::read(scratch.dir / "state", store::JobFilter{});
  std::size_t failed = 0;
  for (const auto& job : listed) failed += job.state == "failed";
  EXPECT_EQ(failed, 4u);
}

}  // namespace
}  // namespace netmc::service
