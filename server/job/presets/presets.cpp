#include "server/job/presets/presets.hpp"

#include <array>
#include <stdexcept>

#include "server/job/presets/preset_studies.hpp"

namespace netmc::presets {
namespace {

struct PresetEntry {
  std::string_view name;
  std::string_view description;
  StudyPlan (*build)();
};

// Every preset, in the order --list-presets prints them: the one list both the lookup and the
// listing read, so they cannot disagree.
constexpr std::array kPresets{
    PresetEntry{"seed001", "paper 001, Table 1: circle r = 10 mm, h = 5 ms, its three controllers", seed001},
    PresetEntry{"seed001-ellipse", "paper 001's plant and gains on a 4:1 ellipse", seed001_ellipse},
    PresetEntry{"seed001-line", "paper 001's plant and gains on a straight line", seed001_line},
    PresetEntry{"seed001-long-delay", "paper 001's circle, loop delay U(2, 8) ms", seed001_long_delay},
    PresetEntry{"seed001-bursty", "paper 001's circle, bursty Markov loop delay", seed001_bursty},
    PresetEntry{"thesis-ellipse", "thesis Table 2-2: 10:1 ellipse, SARC in both frames", thesis_ellipse},
    PresetEntry{"thesis-circle", "thesis Table 2-1: circle r = 4 cm, cases A and B", thesis_circle},
    PresetEntry{"thesis-darc", "thesis Table 3-1 (Exp I, Set1): SARC, DARC, DIARC", thesis_darc},
    PresetEntry{"thesis-darc-sets", "thesis Tables 3-1 and 3-2: Exp I and II under Sets 1-3", thesis_darc_sets},
    PresetEntry{"thesis-cogging", "thesis Tables 4-1 and 4-2: cogging compensation", thesis_cogging},
    PresetEntry{"thesis-ellipse-delay", "the thesis ellipse under loop delay", thesis_ellipse_delay},
    PresetEntry{"thesis-spatial", "thesis ch. 6: GTCF-SARC on a tilted circle, three axes", thesis_spatial},
    PresetEntry{"thesis-dead-zone", "thesis Table 5-1: dead-zone compensation on one axis", thesis_dead_zone},
    PresetEntry{"seed004", "paper 004, Table 4: circle and sharp angle, QFT cross-coupling", seed004},
    PresetEntry{"seed002", "paper 002, Tables 1 and 2: circle and heart, MFA-DTSMC and MFAC", seed002},
};

}  // namespace

std::vector<std::string> preset_names() {
  std::vector<std::string> names;
  for (const auto& preset : kPresets) names.emplace_back(preset.name);
  return names;
}

StudyPlan make_preset(std::string_view name) {
  for (const auto& preset : kPresets) {
    if (preset.name == name) return preset.build();
  }
  std::string expected;
  for (const auto& n : preset_names()) expected += (expected.empty() ? "" : ", ") + n;
  throw std::invalid_argument("--preset: unknown name '" + std::string(name) +
                              "' (expected one of: " + expected + ")");
}

}  // namespace netmc::presets
