// netmc sweep --shard K/N and netmc sweep merge: the parts of a grid joined give the unsharded
// files byte for byte, in any order of the parts; parts of another grid, a missing or a repeated
// part, a foreign file are refused naming the file and the part. Run through the CLI in-process.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "client/sweep_shard.hpp"
#include "tests/client/netmc_in_process.hpp"

namespace netmc::cli {
namespace {

namespace fs = std::filesystem;

struct Scratch {
  fs::path dir = fs::temp_directory_path() / ("netmc_sweep_shard_" + std::to_string(::getpid()));
  Scratch() { fs::create_directories(dir); }
  ~Scratch() { fs::remove_all(dir); }
  std::string operator/(const std::string& name) const { return (dir / name).string(); }
};

std::string slurp(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream content;
  content << file.rdbuf();
  return content.str();
}

// Eight configurations of 0.3 s each: two controllers x two delay bounds x two seeds.
std::vector<std::string> grid_flags() {
  return {"sweep", "-q", "--controller", "adrc,adrc+ilccc", "--delay-max", "1ms,4ms", "--seeds", "1..2",
          "--iterations", "2", "--duration", "0.3s", "--threads", "2"};
}

NetmcOutcome sweep(std::vector<std::string> extra) {
  auto arguments = grid_flags();
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  return run_netmc_captured(arguments);
}

TEST(SweepShard, ParsesKOfNAndRefusesTheRest) {
  const auto shard = parse_sweep_shard("2/3", "--shard");
  EXPECT_EQ(shard.index, 2u);
  EXPECT_EQ(shard.count, 3u);
  EXPECT_TRUE(shard.contains(2));
  EXPECT_TRUE(shard.contains(5));
  EXPECT_FALSE(shard.contains(3));
  for (const char* bad : {"0/3", "4/3", "3", "1/0", "a/b", "1/3/4", "-1/3", "1/100001", ""}) {
    EXPECT_THROW(parse_sweep_shard(bad, "--shard"), std::invalid_argument) << bad;
  }
}

TEST(SweepShard, PartsMergeIntoTheUnshardedFilesByteForByte) {
  Scratch scratch;
  ASSERT_EQ(sweep({"--csv", scratch / "whole.csv", "--json", scratch / "whole.json"}).exit_code, 0);
  for (const char* k : {"1", "2", "3"}) {
    const auto part = sweep({"--shard", std::string(k) + "/3", "--csv", scratch / (std::string("p") + k + ".csv"),
                             "--json", scratch / (std::string("p") + k + ".json")});
    ASSERT_EQ(part.exit_code, 0) << part.err;
    // Part 3 of 3 holds configurations 3 and 6 of 8.
    if (std::string(k) == "3") {
      EXPECT_NE(part.out.find("2 configurations (part 3/3 of 8)"), std::string::npos) << part.out;
    }
  }
  // In any order of the parts.
  const auto csv = run_netmc_captured({"sweep", "merge", scratch / "p3.csv", scratch / "p1.csv", scratch / "p2.csv",
                                       "-o", scratch / "merged.csv"});
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  const auto whole_csv = slurp(scratch / "whole.csv");
  EXPECT_EQ(slurp(scratch / "merged.csv"), whole_csv);
  const auto json = run_netmc_captured({"sweep", "merge", scratch / "p2.json", scratch / "p3.json", scratch / "p1.json"});
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_EQ(json.out, slurp(scratch / "whole.json"));
  // The parts are real parts: each holds only its own configurations (2 iterations each).
  const auto part_two = slurp(scratch / "p2.csv");
  EXPECT_TRUE(part_two.starts_with("# netmc sweep part 2/3 grid="));
  EXPECT_NE(part_two.find("\n2,"), std::string::npos);
  EXPECT_NE(part_two.find("\n5,"), std::string::npos);
  EXPECT_NE(part_two.find("\n8,"), std::string::npos);
  EXPECT_EQ(part_two.find("\n1,"), std::string::npos);
  EXPECT_EQ(part_two.find("\n3,"), std::string::npos);
  EXPECT_EQ(std::count(whole_csv.begin(), whole_csv.end(), '\n'), 1 + 8 * 2);
}

TEST(SweepShard, MergeRefusesMissingRepeatedForeignAndMixedParts) {
  Scratch scratch;
  for (const char* k : {"1", "2"}) {
    ASSERT_EQ(sweep({"--shard", std::string(k) + "/2", "--csv", scratch / (std::string("p") + k + ".csv"), "--json",
                     scratch / (std::string("p") + k + ".json")})
                  .exit_code,
              0);
  }
  // The same shard of another grid (one seed less).
  auto other = grid_flags();
  other[7] = "1";
  other.insert(other.end(), {"--shard", "2/2", "--csv", scratch / "other.csv"});
  ASSERT_EQ(run_netmc_captured(other).exit_code, 0);
  std::ofstream(scratch / "foreign.csv") << "config,e_max_m\n1,0.1\n";
  const auto refused = [&](std::vector<std::string> parts, const std::string& expected) {
    std::vector<std::string> arguments{"sweep", "merge"};
    for (const auto& part : parts) arguments.push_back(scratch / part);
    const auto outcome = run_netmc_captured(arguments);
    EXPECT_EQ(outcome.exit_code, 2) << expected;
    EXPECT_NE(outcome.err.find(expected), std::string::npos) << outcome.err;
    EXPECT_EQ(outcome.out, "");
  };
  refused({"p1.csv"}, "part 2/2 missing");
  refused({"p1.csv", "p1.csv", "p2.csv"}, "part 1/2 given twice");
  refused({"p1.csv", "other.csv"}, "parts of different sweeps");
  refused({"p1.csv", "p2.json"}, "p2.json: a JSON part among CSV parts");
  refused({"foreign.csv", "p2.csv"}, "foreign.csv: not a part of a sweep");
  refused({"no-such.csv"}, "no-such.csv: cannot read the file");
  // A part whose rows were edited to hold another part's configuration.
  std::string edited = slurp(scratch / "p2.csv");
  edited.replace(edited.find("\n2,"), 3, "\n1,");
  std::ofstream(scratch / "edited.csv") << edited;
  refused({"p1.csv", "edited.csv"}, "edited.csv: configuration 1 is not one of part 2/2");
  // Flags: a part needs a file, and its figures come after the merge.
  EXPECT_NE(sweep({"--shard", "1/2"}).err.find("--shard: a part is for netmc sweep merge"), std::string::npos);
  EXPECT_NE(sweep({"--shard", "3/2", "--csv", scratch / "x.csv"}).err.find("--shard: expected K/N"),
            std::string::npos);
}

}  // namespace
}  // namespace netmc::cli
