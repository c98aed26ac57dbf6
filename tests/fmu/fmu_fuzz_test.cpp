// Bounded fuzz passes from fixed seeds: 2000 mutations of the test FMU's modelDescription.xml
// through the parser, and 300 damaged copies of the test FMU (truncated, overwritten, random)
// through the whole loader. Each either loads or throws std::invalid_argument; nothing crashes
// (the sanitizer build runs these too) and nothing else is thrown.

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <random>
#include <sstream>
#include <string>

#include "server/fmu/model_description.hpp"
#include "test_fmu.hpp"

namespace netmc::plant::fmu {
namespace {

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// One to four edits: a flipped byte, a cut, a copied slice, an XML token, a truncation.
std::string mutated(std::string text, std::mt19937_64& random) {
  static const std::array<std::string, 16> kTokens{
      "<",  ">",  "\"", "&", "&amp;", "<!--", "-->", "<![CDATA[", "]]>", "<ScalarVariable name=\"x\">",
      "</ScalarVariable>", "<Real start=\"1e999\"/>", "fmiVersion=\"2.0\"", "<CoSimulation/>", "\x01", "\xff"};
  const auto at = [&](std::size_t size) {
    return size == 0 ? std::size_t{0} : static_cast<std::size_t>(random() % (size + 1));
  };
  const int edits = 1 + static_cast<int>(random() % 4);
  for (int e = 0; e < edits; ++e) {
    switch (random() % 6) {
      case 0:
        if (!text.empty()) text[at(text.size() - 1)] ^= static_cast<char>(1u << (random() % 8));
        break;
      case 1: {
        const std::size_t from = at(text.size());
        text.erase(from, random() % 200);
        break;
      }
      case 2: {
        const std::size_t from = at(text.size());
        const std::string slice = text.substr(from, random() % 300);
        text.insert(at(text.size()), slice);
        break;
      }
      case 3:
        text.insert(at(text.size()), kTokens[random() % kTokens.size()]);
        break;
      case 4:
        text.resize(at(text.size()));
        break;
      default: {
        const std::size_t from = at(text.size());
        for (std::size_t i = from; i < text.size() && i < from + 8; ++i) text[i] = static_cast<char>(random());
        break;
      }
    }
  }
  return text;
}

TEST(FmuFuzz, ModelDescriptionParserAcceptsOrRefusesCleanly) {
  const std::string original = file_bytes(NETMC_TEST_FMU_TEMPLATE_XML);
  ASSERT_FALSE(original.empty());
  std::mt19937_64 random(2024);
  int accepted = 0, refused = 0;
  for (int i = 0; i < 2000; ++i) {
    const std::string xml = mutated(original, random);
    try {
      const ModelDescription d = parse_model_description(xml, "fuzz.fmu");
      EXPECT_LE(d.variables.size(), kMaxVariables);
      ++accepted;
    } catch (const std::invalid_argument&) {
      ++refused;
    }
  }
  std::cout << "[ figures  ] modelDescription.xml fuzz: " << accepted << " accepted, " << refused << " refused\n";
  EXPECT_GT(refused, 0);
}

class ScratchDirectory {
 public:
  ScratchDirectory()
      : path_(std::filesystem::temp_directory_path() / ("netmc-fmu-fuzz-" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path_);
  }
  ~ScratchDirectory() { std::filesystem::remove_all(path_); }
  std::string write(const std::string& name, const std::string& bytes) const {
    const auto file = path_ / name;
    std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
    return file.string();
  }

 private:
  std::filesystem::path path_;
};

TEST(FmuFuzz, DamagedArchivesLoadOrAreRefusedCleanly) {
  const std::string original = file_bytes(NETMC_TEST_FMU_SEED001_AXIS);
  ASSERT_GT(original.size(), 100u);
  const ScratchDirectory scratch;
  std::mt19937_64 random(7);
  int loaded = 0, refused = 0;
  for (int i = 0; i < 300; ++i) {
    std::string bytes;
    switch (i % 3) {
      case 0:  // truncated anywhere, the empty file included
        bytes = original.substr(0, static_cast<std::size_t>(random() % original.size()));
        break;
      case 1: {  // a few bytes overwritten, often in the headers and the central directory
        bytes = original;
        const int count = 1 + static_cast<int>(random() % 8);
        for (int k = 0; k < count; ++k) {
          const bool near_end = random() % 2 == 0;
          const std::size_t span = near_end ? std::min<std::size_t>(400, bytes.size()) : bytes.size();
          bytes[bytes.size() - 1 - static_cast<std::size_t>(random() % span)] = static_cast<char>(random());
        }
        break;
      }
      default: {  // random bytes, sometimes behind a zip signature
        bytes.resize(static_cast<std::size_t>(random() % 4096));
        for (char& c : bytes) c = static_cast<char>(random());
        if (random() % 2 == 0) bytes.insert(0, "PK\x03\x04");
        break;
      }
    }
    const std::string path = scratch.write("damaged.fmu", bytes);
    try {
      AxisSet set = make_fmu_plant_set(path, 1);
      set.axes[0]->reset(0.0, 0.0);
      set.axes[0]->advance(1e-3, 1.0);
      ++loaded;
    } catch (const std::invalid_argument&) {
      ++refused;
    }
  }
  std::cout << "[ figures  ] archive fuzz: " << loaded << " loaded, " << refused << " refused\n";
  EXPECT_GT(refused, 200);
}

}  // namespace
}  // namespace netmc::plant::fmu
