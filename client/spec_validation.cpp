#include "client/spec_validation.hpp"

#include <google/protobuf/descriptor.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "server/job/job_builder.hpp"
#include "server/job/legacy_spec.hpp"

namespace netmc::cli {
namespace {

using google::protobuf::Descriptor;
using google::protobuf::FieldDescriptor;
using nlohmann::json;

enum class Range { any, non_negative, positive, probability };

bool ends_with(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Ranges by field name (and path where the name alone is ambiguous).
Range range_of(const std::string& path, const std::string& name) {
  // sample_period_s, divergence_limit_m and the like may be 0: "use the default".
  static const std::set<std::string> positive{"radius_m", "period_s", "semi_axis_x_m", "semi_axis_y_m",
                                              "scale_s", "shape"};
  static const std::set<std::string> probability{"p", "p_good_to_bad", "p_bad_to_good",
                                                 "loss_in_good", "loss_in_bad"};
  static const std::set<std::string> any{"center_x_m", "center_y_m", "center_z_m", "x0_m", "y0_m", "x1_m", "y1_m",
                                         "start_angle_rad", "normal_x", "normal_y", "normal_z",
                                         "start_x", "start_y", "start_z",
                                         // multi-sine terms; a dead zone's left break point
                                         "offset_m", "amplitude_m", "phase_rad", "left_break_v",
                                         "value",  // a plant parameter (its plant checks its range)
                                         // a disturbance pushes either way
                                         "amplitude", "constant"};
  // A controller's gains: their family's descriptor checks each when the job is built.
  if (path.rfind("controller.gains.", 0) == 0) return Range::any;
  if (ends_with(path, "line.duration_s")) return Range::positive;
  if (positive.contains(name)) return Range::positive;
  if (probability.contains(name)) return Range::probability;
  if (any.contains(name)) return Range::any;
  return Range::non_negative;
}

std::string kind_of(const json& value) {
  switch (value.type()) {
    case json::value_t::object: return "an object";
    case json::value_t::array: return "a list";
    case json::value_t::string: return "the text " + value.dump();
    case json::value_t::boolean: return value.dump();
    case json::value_t::null: return "null";
    default: return value.dump();
  }
}

class Validator {
 public:
  explicit Validator(std::string origin) : origin_(std::move(origin)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& message) const {
    throw std::invalid_argument(origin_ + ": " + (path.empty() ? std::string() : path + ": ") + message);
  }

  void message(const json& value, const Descriptor* descriptor, const std::string& path) const {
    if (!value.is_object()) fail(path, "expected an object {...}, got " + kind_of(value));
    std::set<const google::protobuf::OneofDescriptor*> oneofs_seen;
    for (const auto& [key, member] : value.items()) {
      const FieldDescriptor* field = descriptor->FindFieldByName(key);
      if (!field) {
        for (int i = 0; i < descriptor->field_count() && !field; ++i) {
          if (descriptor->field(i)->json_name() == key) field = descriptor->field(i);
        }
      }
      const std::string field_path = path.empty() ? key : path + "." + key;
      if (!field) {
        std::string expected;
        for (int i = 0; i < descriptor->field_count(); ++i) {
          if (i > 0) expected += ", ";
          expected += descriptor->field(i)->name();
        }
        fail(field_path, "unknown field (expected one of: " + expected + ")");
      }
      if (member.is_null()) continue;  // protobuf: the default
      if (const auto* oneof = field->real_containing_oneof()) {
        if (!oneofs_seen.insert(oneof).second) {
          std::string members;
          for (int i = 0; i < oneof->field_count(); ++i) {
            if (i > 0) members += ", ";
            members += oneof->field(i)->name();
          }
          fail(path.empty() ? oneof->name() : path, "give only one of: " + members);
        }
      }
      if (field->is_map()) {
        // A map is an object whose keys are the map's (a gains group's name, a key, an axis).
        if (!member.is_object()) fail(field_path, "expected an object {...}, got " + kind_of(member));
        for (const auto& [map_key, map_value] : member.items()) {
          if (map_key.empty() || map_key.size() > 64) fail(field_path, "expected keys of 1-64 characters");
          single(map_value, field->message_type()->map_value(), field_path + "." + map_key);
        }
      } else if (field->is_repeated()) {
        if (!member.is_array()) fail(field_path, "expected a list [...], got " + kind_of(member));
        for (std::size_t i = 0; i < member.size(); ++i) {
          single(member[i], field, field_path + "[" + std::to_string(i) + "]");
        }
      } else {
        single(member, field, field_path);
      }
    }
  }

 private:
  void single(const json& value, const FieldDescriptor* field, const std::string& path) const {
    switch (field->cpp_type()) {
      case FieldDescriptor::CPPTYPE_MESSAGE:
        message(value, field->message_type(), path);
        return;
      case FieldDescriptor::CPPTYPE_DOUBLE:
      case FieldDescriptor::CPPTYPE_FLOAT:
        number(value, field, path);
        return;
      case FieldDescriptor::CPPTYPE_UINT32:
      case FieldDescriptor::CPPTYPE_UINT64:
      case FieldDescriptor::CPPTYPE_INT32:
      case FieldDescriptor::CPPTYPE_INT64:
        integer(value, field, path);
        return;
      case FieldDescriptor::CPPTYPE_BOOL:
        if (!value.is_boolean()) fail(path, "expected true or false, got " + kind_of(value));
        return;
      case FieldDescriptor::CPPTYPE_STRING:
        if (!value.is_string()) fail(path, "expected a text in quotes, got " + kind_of(value));
        return;
      default:
        fail(path, "unsupported field type");
    }
  }

  void number(const json& value, const FieldDescriptor* field, const std::string& path) const {
    if (!value.is_number()) fail(path, "expected a number, got " + kind_of(value));
    const double x = value.get<double>();
    const std::string got = ", got " + value.dump();
    switch (range_of(path, field->name())) {
      case Range::positive:
        if (!(x > 0.0)) fail(path, "expected a positive number" + got);
        break;
      case Range::non_negative:
        if (!(x >= 0.0)) fail(path, "expected a non-negative number" + got);
        break;
      case Range::probability:
        if (!(x >= 0.0 && x <= 1.0)) fail(path, "expected a number from 0 to 1" + got);
        break;
      case Range::any:
        break;
    }
  }

  void integer(const json& value, const FieldDescriptor* field, const std::string& path) const {
    const bool is_unsigned = field->cpp_type() == FieldDescriptor::CPPTYPE_UINT32 ||
                             field->cpp_type() == FieldDescriptor::CPPTYPE_UINT64;
    const bool wide = field->cpp_type() == FieldDescriptor::CPPTYPE_UINT64 ||
                      field->cpp_type() == FieldDescriptor::CPPTYPE_INT64;
    const char* expected = is_unsigned ? "expected a non-negative whole number" : "expected a whole number";
    if (value.is_string() && wide) {  // protobuf's JSON mapping writes 64-bit integers as text
      const std::string text = value.get<std::string>();
      const bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
      if (!digits) fail(path, std::string(expected) + ", got " + kind_of(value));
      return;
    }
    if (value.is_number_unsigned()) {
      if (!wide && value.get<std::uint64_t>() > 0xffffffffULL) fail(path, std::string(expected) + " below 2^32, got " + value.dump());
      return;
    }
    if (value.is_number_integer() && !is_unsigned) return;
    if (value.is_number_float()) {
      const double x = value.get<double>();
      if (std::floor(x) == x && (!is_unsigned || x >= 0.0) && std::abs(x) < 4e9) return;
    }
    fail(path, std::string(expected) + ", got " + kind_of(value));
  }

  std::string origin_;
};

}  // namespace

void validate_job_spec_json(const std::string& original, const std::string& origin) {
  // A 0.1 spec's typed gains are checked as the gains they stand for (unparsable text comes back
  // unchanged, so a syntax error's line and column are the file's).
  const std::string text = job::upgrade_legacy_spec_json(original);
  json document;
  try {
    document = json::parse(text);
  } catch (const json::parse_error& error) {
    // Line and column of the byte where parsing stopped.
    std::size_t line = 1, column = 1;
    for (std::size_t i = 0; i + 1 < error.byte && i < text.size(); ++i) {
      if (text[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    throw std::invalid_argument(origin + ":" + std::to_string(line) + ":" + std::to_string(column) +
                                ": not valid JSON");
  }
  Validator(origin).message(document, netmc::v1::JobSpec::descriptor(), "");
}

netmc::v1::JobSpec parse_job_spec_file_text(const std::string& text, const std::string& origin) {
  validate_job_spec_json(text, origin);
  return job::parse_job_spec_json(text, origin);
}

}  // namespace netmc::cli
