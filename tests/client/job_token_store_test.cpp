// The job tokens netmc submit keeps for netmc cancel: private (file 0600 in a 0700 directory),
// named by server and job, found again only for that server and job, never written through a
// planted symlink.
#include "client/job_token_store.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace netmc::cli {
namespace {

namespace fs = std::filesystem;

struct ScratchStateHome {
  // One per test (ctest runs each test in a process of its own, so the environment is its own).
  ScratchStateHome()
      : path(fs::temp_directory_path() /
             ("netmc_job_tokens_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()))) {
    fs::remove_all(path);
    fs::create_directories(path);
    ::setenv("XDG_STATE_HOME", path.c_str(), 1);
  }
  ~ScratchStateHome() { fs::remove_all(path); }
  fs::path path;
};

TEST(JobTokenStore, SavedTokenIsPrivateAndFoundForItsServerAndJobOnly) {
  const ScratchStateHome home;
  const std::string token(64, 'a');
  const fs::path saved = save_job_token("127.0.0.1:7300", 5, token);
  EXPECT_EQ(saved, home.path / "netmc" / "jobs" / "127.0.0.1_7300-job-5.token");
  EXPECT_EQ(fs::status(saved).permissions() & fs::perms::all, fs::perms::owner_read | fs::perms::owner_write);
  EXPECT_EQ(fs::status(saved.parent_path()).permissions() & fs::perms::all, fs::perms::owner_all);
  EXPECT_EQ(saved_job_token("127.0.0.1:7300", 5), token);
  EXPECT_EQ(saved_job_token("127.0.0.1:7300", 6), std::nullopt);
  EXPECT_EQ(saved_job_token("127.0.0.1:7301", 5), std::nullopt);
}

TEST(JobTokenStore, TokenNotShapedAsTheServerMakesThemIsNotKept) {
  // The token arrives from the network: a hostile server's text must not land in the user's files.
  const ScratchStateHome home;
  for (const std::string& token : {std::string("abc"), std::string(257, 'a'), std::string(32, 'a') + "\nrm -rf /",
                                   std::string(32, 'g')}) {
    EXPECT_THROW(save_job_token("127.0.0.1:7300", 7, token), std::runtime_error) << token.size();
  }
  EXPECT_EQ(saved_job_token("127.0.0.1:7300", 7), std::nullopt);
  EXPECT_NO_THROW(save_job_token("127.0.0.1:7300", 7, std::string(64, 'f')));
}

TEST(JobTokenStore, PlantedSymlinkIsNotWrittenThrough) {
  const ScratchStateHome home;
  const fs::path directory = home.path / "netmc" / "jobs";
  fs::create_directories(directory);
  const fs::path victim = home.path / "victim";
  std::ofstream(victim) << "precious";
  fs::create_symlink(victim, directory / "127.0.0.1_7300-job-5.token");
  EXPECT_THROW(save_job_token("127.0.0.1:7300", 5, std::string(64, 'a')), std::runtime_error);
  std::ifstream file(victim);
  std::string content;
  std::getline(file, content);
  EXPECT_EQ(content, "precious");
}

TEST(JobTokenStore, ForgottenTokenIsGoneForItsJobOnly) {
  const ScratchStateHome home;
  const fs::path five = save_job_token("127.0.0.1:7300", 5, std::string(64, 'a'));
  const fs::path six = save_job_token("127.0.0.1:7300", 6, std::string(64, 'b'));
  EXPECT_TRUE(forget_job_token("127.0.0.1:7300", 5));
  EXPECT_FALSE(fs::exists(five));
  EXPECT_EQ(saved_job_token("127.0.0.1:7300", 5), std::nullopt);
  EXPECT_TRUE(fs::exists(six));
  EXPECT_FALSE(forget_job_token("127.0.0.1:7300", 5));  // already gone: nothing to do, no error
}

}  // namespace
}  // namespace netmc::cli
