// Seeded mutation fuzzing with a fixed budget: what comes from the network or a file must end in
// a result or a std::invalid_argument (job specs) / FrameError (frames), never in a crash, a
// hang or another exception. The seeds are real specs; the mutations flip, insert, delete and
// copy bytes of their protobuf encoding and JSON text. Deterministic: the same cases every run.
// The same tests run under AddressSanitizer and UndefinedBehaviorSanitizer in CI (.ci/run).
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <google/protobuf/stubs/logging.h>

#include "idl/management.pb.h"
#include "server/job/job_builder.hpp"
#include "server/management/frame_codec.hpp"

namespace netmc::job {
namespace {

// Budget: cases per test (each builds at most a short job; the whole file takes a few seconds).
constexpr int kCases = 20000;

// protobuf logs every invalid UTF-8 string it meets while parsing: thousands of lines here.
const bool kQuietProtobuf = [] {
  google::protobuf::SetLogHandler(nullptr);
  return true;
}();

std::vector<netmc::v1::JobSpec> seed_specs() {
  std::vector<netmc::v1::JobSpec> seeds;
  const char* texts[] = {
      R"({"trajectory": {"circle": {"radius_m": 0.01, "center_x_m": 0.05, "center_y_m": 0.05, "period_s": 8}},
          "controller": {"name": "adrc+ilccc"}, "duration_s": 0.2, "iterations": 2,
          "downlink": {"delay": {"uniform": {"min_s": 0.0003, "max_s": 0.0008}}}})",
      R"({"trajectory": {"ellipse": {"semi_axis_x_m": 0.04, "semi_axis_y_m": 0.02, "period_s": 4}},
          "plant": "linmotor", "controller": {"name": "gtcf-sarc", "task_space": {"lambda_c": 100}},
          "sample_period_s": 0.001, "duration_s": 0.1, "command_limit": 8,
          "uplink": {"delay": {"trace": {"delays_s": [0.001, 0.002]}}, "loss": {"bernoulli": {"p": 0.1}}}})",
      R"({"trajectory": {"polyline": {"points": [{"x_m": 0}, {"x_m": 0.02}, {"x_m": 0.02, "y_m": 0.01}],
          "max_speed_m_s": 0.01, "max_acceleration_m_s2": 0.1}}, "controller": {"name": "pid+pidccc"},
          "duration_s": 0.1, "sensor": {"resolution_m": 1e-6}})",
      R"({"trajectory": {"spatial_circle": {"radius_m": 0.05, "normal_x": -1, "normal_y": 1, "start_z": 1,
          "period_s": 1.5, "revolutions": 0.1}}, "plant": "linmotor", "controller": {"name": "gtcf-sarc"},
          "sample_period_s": 0.001})",
  };
  for (const char* text : texts) {
    auto spec = parse_job_spec_json(text, "seed");
    apply_defaults(spec);
    seeds.push_back(spec);
  }
  return seeds;
}

std::string mutate(std::string bytes, std::mt19937_64& random) {
  std::uniform_int_distribution<int> kind(0, 4);
  const int edits = 1 + static_cast<int>(random() % 4);
  for (int e = 0; e < edits; ++e) {
    const std::size_t at = bytes.empty() ? 0 : random() % bytes.size();
    switch (kind(random)) {
      case 0:
        if (!bytes.empty()) bytes[at] = static_cast<char>(bytes[at] ^ (1 << (random() % 8)));
        break;
      case 1:
        bytes.insert(at, 1, static_cast<char>(random() % 256));
        break;
      case 2:
        if (!bytes.empty()) bytes.erase(at, 1 + random() % 8);
        break;
      case 3: {  // copy a run elsewhere (repeats fields, grows lists)
        const std::size_t from = bytes.empty() ? 0 : random() % bytes.size();
        bytes.insert(at, bytes.substr(from, 1 + random() % 32));
        break;
      }
      default:
        if (!bytes.empty()) bytes[at] = static_cast<char>(random() % 256);
        break;
    }
  }
  return bytes;
}

// A spec is built or refused with std::invalid_argument; anything else fails the test.
void build_or_refuse(const netmc::v1::JobSpec& spec, int& built, int& refused) {
  try {
    reject_file_references(spec);
    build_contour_job(spec);
    ++built;
  } catch (const std::invalid_argument&) {
    ++refused;
  }
}

TEST(HostileInputFuzz, MutatedSpecEncodingsAreBuiltOrRefusedWithAMessage) {
  const auto seeds = seed_specs();
  std::mt19937_64 random(20261124);
  int parsed = 0, built = 0, refused = 0;
  for (int i = 0; i < kCases; ++i) {
    const std::string bytes = mutate(seeds[static_cast<std::size_t>(i) % seeds.size()].SerializeAsString(), random);
    netmc::v1::JobSpec spec;
    if (!spec.ParseFromString(bytes)) continue;
    ++parsed;
    // Keep each case short: the point is the checks, not long simulations.
    if (spec.duration_s() > 1.0 || spec.duration_s() == 0.0) spec.set_duration_s(0.1);
    build_or_refuse(spec, built, refused);
  }
  // The mutations reach the builder (most encodings still parse) and both outcomes occur.
  EXPECT_GT(parsed, kCases / 20);
  EXPECT_GT(built, 0);
  EXPECT_GT(refused, 0);
  RecordProperty("parsed", parsed);
  RecordProperty("built", built);
  RecordProperty("refused", refused);
}

TEST(HostileInputFuzz, MutatedJsonSpecsAreParsedOrRefusedWithAMessage) {
  const auto seeds = seed_specs();
  std::mt19937_64 random(4242);
  int parsed = 0, refused = 0;
  for (int i = 0; i < kCases; ++i) {
    const std::string text = mutate(to_json(seeds[static_cast<std::size_t>(i) % seeds.size()]), random);
    try {
      auto spec = parse_job_spec_json(text, "fuzz.json");
      ++parsed;
      if (spec.duration_s() > 1.0 || spec.duration_s() == 0.0) spec.set_duration_s(0.1);
      int built = 0, rejected = 0;
      build_or_refuse(spec, built, rejected);
    } catch (const std::invalid_argument&) {
      ++refused;
    }
  }
  EXPECT_GT(parsed, 0);
  EXPECT_GT(refused, 0);
}

TEST(HostileInputFuzz, MutatedFramesDecodeOrFailWithAFrameError) {
  std::mt19937_64 random(7);
  netmc::v1::Request request;
  request.set_request_id(3);
  *request.mutable_submit()->mutable_spec() = seed_specs().front();
  const std::string valid = management::encode_frame(request) + management::encode_frame(request);
  int requests = 0, frame_errors = 0;
  for (int i = 0; i < kCases; ++i) {
    const std::string bytes = mutate(valid, random);
    management::FrameDecoder decoder;
    // Fed in random splits, as a socket would deliver them.
    std::size_t at = 0;
    try {
      while (at < bytes.size()) {
        const std::size_t n = std::min<std::size_t>(bytes.size() - at, 1 + random() % 64);
        decoder.feed(bytes.data() + at, n);
        at += n;
        while (auto payload = decoder.next()) {
          netmc::v1::Request parsed;
          if (parsed.ParseFromString(*payload)) ++requests;
        }
      }
    } catch (const management::FrameError&) {
      ++frame_errors;
    }
  }
  EXPECT_GT(requests, 0);
  EXPECT_GT(frame_errors, 0);
}

}  // namespace
}  // namespace netmc::job
