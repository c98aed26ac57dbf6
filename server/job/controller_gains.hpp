#pragma once
// The gains of a job's controller as its spec carries them (ControllerSpec.gains: one Gains per
// group, by the group's name, each with an axis's own where it differs): the groups' keys as a
// family declares them, checks of a spec against them, the reader the families build from, and
// the writers of presets and flags.

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "idl/job.pb.h"
#include "server/job/quantity_text.hpp"

namespace netmc::job {

enum class GainCheck { finite, positive, non_negative, whole };

// One key of a gains group.
struct GainKey {
  enum class Kind { number, choice, list };
  GainKey(std::string name_, std::string meaning_, std::string default_text_, Kind kind_ = Kind::number,
          GainCheck check_ = GainCheck::finite, std::vector<std::string> choices_ = {}, std::size_t list_size_ = 0,
          std::vector<std::string> flag_aliases_ = {}, Quantity quantity_ = Quantity::plain)
      : name(std::move(name_)),
        meaning(std::move(meaning_)),
        default_text(std::move(default_text_)),
        kind(kind_),
        check(check_),
        choices(std::move(choices_)),
        list_size(list_size_),
        flag_aliases(std::move(flag_aliases_)),
        quantity(quantity_) {}

  std::string name;           // in the spec and in the flag: "w0"
  std::string meaning;        // "observer bandwidth (rad/s)"
  std::string default_text;   // "100", for help and the docs
  Kind kind = Kind::number;
  GainCheck check = GainCheck::finite;
  std::vector<std::string> choices;        // Kind::choice: the words it takes, the first the default
  std::size_t list_size = 0;               // Kind::list: how many numbers
  std::vector<std::string> flag_aliases;   // short names in the flag ("q" for q_cutoff_hz)
  Quantity quantity = Quantity::plain;     // the units a flag may give (10mm, 5ms, ...)
};

// A group of gains: one family's, or settings several families share (task_space).
struct GainGroup {
  std::string name;       // the key in ControllerSpec.gains
  std::string flag;       // "--adrc"
  std::string summary;    // what it is, for the flag's help
  bool per_axis = false;  // AXIS.KEY=VALUE: an axis's own
  std::vector<GainKey> keys;

  const GainKey* key(std::string_view name) const;
  // "--adrc r0=..,w0=..,observer=euler|zoh" with per-axis entries AXIS.KEY=VALUE where allowed.
  std::string syntax() const;
};

// Throws std::invalid_argument naming the field ("controller.gains.adrc.w1: unknown key ...") for
// a group not in `groups`, a key the group does not have, a value of the wrong kind, outside its
// check or not finite, a list of the wrong length, an axis not of the job or per-axis values in a
// group that takes none.
void check_gains(const netmc::v1::ControllerSpec& spec, const std::vector<const GainGroup*>& groups,
                 const std::vector<std::string>& axis_names);

// What the families read: each key for one axis of the group, the axis's own value where it has
// one, else the group's (checked beforehand by check_gains).
class GainsReader {
 public:
  GainsReader(const netmc::v1::ControllerSpec& spec, std::vector<std::string> axis_names);

  // Sets `target` if the key is given; true if it was.
  bool read(std::string_view group, std::string_view key, std::size_t axis, double& target) const;
  bool read(std::string_view group, std::string_view key, double& target) const { return read(group, key, 0, target); }
  std::optional<std::string> choice(std::string_view group, std::string_view key, std::size_t axis = 0) const;
  std::optional<std::vector<double>> list(std::string_view group, std::string_view key, std::size_t axis = 0) const;
  bool has_axis_values(std::string_view group, std::size_t axis) const;
  // The spec's path of a key, for messages: "controller.gains.adrc.w0" (".axes.y.w0" for an axis).
  std::string field(std::string_view group, std::string_view key, std::size_t axis = 0) const;
  const std::vector<std::string>& axis_names() const { return axis_names_; }

 private:
  const netmc::v1::AxisGains* axis_gains(std::string_view group, std::size_t axis) const;
  const netmc::v1::Gains* group(std::string_view name) const;

  const netmc::v1::ControllerSpec& spec_;
  std::vector<std::string> axis_names_;
};

// Writers for presets: the group's value (or the axis's own).
void set_gain(netmc::v1::ControllerSpec& spec, const std::string& group, const std::string& key, double value);
void set_axis_gain(netmc::v1::ControllerSpec& spec, const std::string& group, const std::string& axis,
                   const std::string& key, double value);
void set_gain_choice(netmc::v1::ControllerSpec& spec, const std::string& group, const std::string& key,
                     const std::string& choice);

// A group's flag text, KEY=VALUE[,AXIS.KEY=VALUE...], into the spec's gains of that group (over
// what is there). `axis_names`: the job's axes, for per-axis entries. Throws std::invalid_argument
// naming the flag, the key and the expected form.
void parse_gain_flag(std::string_view text, const GainGroup& group, const std::vector<std::string>& axis_names,
                     netmc::v1::ControllerSpec& spec);

}  // namespace netmc::job
