// Output files written through exclusive temporaries: a planted symlink, at the target or at
// the old fixed temporary name, never redirects a write; a failed write leaves nothing behind.
#include "client/exclusive_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>

namespace netmc::cli {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

struct ScratchDirectory {
  // One per test: ctest runs the tests of this file at the same time.
  ScratchDirectory()
      : path(fs::temp_directory_path() /
             ("netmc_exclusive_file_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()))) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~ScratchDirectory() { fs::remove_all(path); }
  fs::path path;
};

TEST(ExclusiveFile, PlantedSymlinksRedirectNoWrite) {
  const ScratchDirectory dir;
  const auto victim = dir.path / "victim";
  std::ofstream(victim) << "precious";
  const auto target = dir.path / "results.json";
  fs::create_symlink(victim, dir.path / "results.json.partial");  // the old fixed temporary name
  write_file_atomically(target.string(), "first");
  EXPECT_EQ(read_text(victim), "precious");
  EXPECT_EQ(read_text(target), "first");
  // A symlink at the target itself is replaced, not written through.
  fs::remove(target);
  fs::create_symlink(victim, target);
  write_file_atomically(target.string(), "second");
  EXPECT_EQ(read_text(victim), "precious");
  EXPECT_FALSE(fs::is_symlink(target));
  EXPECT_EQ(read_text(target), "second");
  // Nothing else is left: the victim, the target and the planted link.
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir.path)) names.insert(entry.path().filename().string());
  EXPECT_EQ(names, (std::set<std::string>{"victim", "results.json", "results.json.partial"}));
}

TEST(ExclusiveFile, TemporariesAreFreshRegularFilesWithUnpredictableNames) {
  const ScratchDirectory dir;
  const auto target = dir.path / "contour.png";
  const auto first = create_exclusive_temporary(target);
  const auto second = create_exclusive_temporary(target);
  EXPECT_NE(first, second);
  for (const auto& path : {first, second}) {
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(path))) << path;
    EXPECT_EQ(fs::file_size(path), 0u);
    EXPECT_EQ(path.parent_path(), dir.path);
    EXPECT_EQ(path.filename().string().rfind("contour.png.", 0), 0u) << path;
    EXPECT_EQ(fs::status(path).permissions() & fs::perms::all,
              fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read | fs::perms::others_read);
  }
}

TEST(ExclusiveFile, AFailedWriteNamesThePathAndLeavesNothing) {
  const ScratchDirectory dir;
  const auto target = dir.path / "missing" / "out.json";
  try {
    write_file_atomically(target.string(), "x");
    ADD_FAILURE() << "expected an error";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(target.string()), std::string::npos) << error.what();
  }
  EXPECT_TRUE(fs::is_empty(dir.path));
}

}  // namespace
}  // namespace netmc::cli
