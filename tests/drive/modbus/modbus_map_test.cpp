// The Modbus register map: default-map.json says what default_modbus_map() says, a hostile map
// file is refused with one message naming the key path and the expected form, and values scale
// to register words and back or are refused when they do not fit.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "server/drive/modbus/modbus_map.hpp"
#include "server/drive/modbus/modbus_map_file.hpp"

namespace netmc::drive::modbus {
namespace {

using nlohmann::json;

// A valid map file, as JSON to mutate.
json valid_map() {
  return json::parse(R"({
    "format": "netmc-modbus-map", "version": 1, "unit_id": 3, "high_word_first": false, "job_mode": "csv",
    "registers": {
      "statusword": {"address": 100, "type": "uint16"},
      "modes_of_operation_display": {"address": 101, "type": "int16"},
      "error_code": {"address": 102, "type": "uint16"},
      "position_actual": {"address": 103, "type": "int32", "scale": 1e6},
      "controlword": {"address": 200, "type": "uint16"},
      "modes_of_operation": {"address": 201, "type": "uint16"},
      "target_position": {"address": 202, "type": "int32", "scale": 1e6},
      "target_velocity": {"address": 204, "type": "int32", "scale": -1e3},
      "target_torque": {"address": 206, "type": "int16", "scale": 100}
    }
  })");
}

// The message `text` is refused with; fails the test if it is accepted.
std::string refusal(const std::string& text) {
  try {
    parse_modbus_map(text, "map file x.json");
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  ADD_FAILURE() << "accepted: " << text.substr(0, 200);
  return {};
}

std::string refusal(const json& map) { return refusal(map.dump()); }
std::string refusal(const char* text) { return refusal(std::string(text)); }

TEST(ModbusMap, TheDefaultFileSaysWhatTheCodesDefaultSays) {
  const ModbusMap file = load_modbus_map(NETMC_DEFAULT_MODBUS_MAP);
  const ModbusMap code = default_modbus_map();
  for (const auto& info : drive_objects()) {
    SCOPED_TRACE(info.key);
    ASSERT_EQ(file.find(info.object).has_value(), code.find(info.object).has_value());
    if (!code.find(info.object)) continue;
    EXPECT_EQ(file.at(info.object).address, code.at(info.object).address);
    EXPECT_EQ(file.at(info.object).type, code.at(info.object).type);
    EXPECT_EQ(file.at(info.object).scale, code.at(info.object).scale);
  }
  EXPECT_EQ(file.high_word_first, code.high_word_first);
  EXPECT_EQ(file.unit_id, code.unit_id);
  EXPECT_EQ(file.job_mode, code.job_mode);
  EXPECT_FALSE(file.limits.any());
  EXPECT_FALSE(code.limits.any());
  EXPECT_EQ(file.origin, std::string("map file ") + NETMC_DEFAULT_MODBUS_MAP);
  EXPECT_NO_THROW(code.validate());
}

TEST(ModbusMap, TheDefaultMapKeepsWhatANodeReadsEachCycleInOneBlock) {
  const ModbusMap map = default_modbus_map();
  std::vector<RegisterPlacement> inputs;
  for (const DriveObject object : {DriveObject::statusword, DriveObject::modes_of_operation_display,
                                   DriveObject::error_code, DriveObject::position_actual,
                                   DriveObject::velocity_actual, DriveObject::torque_actual}) {
    inputs.push_back(map.at(object));
  }
  std::sort(inputs.begin(), inputs.end(), [](const auto& a, const auto& b) { return a.address < b.address; });
  for (std::size_t i = 1; i < inputs.size(); ++i) {
    EXPECT_EQ(inputs[i].address, inputs[i - 1].address + inputs[i - 1].count());
  }
  EXPECT_EQ(inputs.front().address, 0);
}

TEST(ModbusMap, AValidFileIsReadWithItsSettingsAndLimits) {
  json text = valid_map();
  text["limits"] = {{"command", 8}, {"position_window_m", {-0.05, 0.25}}, {"velocity_m_s", 0.4}, {"slew_per_s", 500}};
  text["description"] = "lab drive";
  const ModbusMap map = parse_modbus_map(text.dump(), "map file lab.json");
  EXPECT_EQ(map.unit_id, 3);
  EXPECT_FALSE(map.high_word_first);
  EXPECT_EQ(map.job_mode, OperationMode::csv);
  EXPECT_FALSE(map.has(DriveObject::velocity_actual));
  EXPECT_EQ(map.at(DriveObject::target_velocity).scale, -1e3);
  EXPECT_EQ(map.limits.command, 8.0);
  EXPECT_EQ(map.limits.position_min_m, -0.05);
  EXPECT_EQ(map.limits.position_max_m, 0.25);
  EXPECT_EQ(map.limits.velocity_m_s, 0.4);
  EXPECT_EQ(map.limits.slew_per_s, 500.0);
  // Comments are allowed.
  EXPECT_NO_THROW(parse_modbus_map("// a lab's drive\n" + valid_map().dump(), "map file lab.json"));
}

TEST(ModbusMap, MalformedJsonIsRefused) {
  EXPECT_NE(refusal("{\"format\": ").find("map file x.json: not valid JSON: "), std::string::npos);
  EXPECT_NE(refusal("[1, 2]").find("map file x.json: (top level): expected a JSON object"), std::string::npos);
}

TEST(ModbusMap, UnknownAndRepeatedKeysAreRefused) {
  json top = valid_map();
  top["colour"] = "red";
  EXPECT_NE(refusal(top).find("map file x.json: colour: unknown key (expected one of: format, version,"),
            std::string::npos);
  json inner = valid_map();
  inner["registers"]["statusword"]["offset"] = 1;
  EXPECT_NE(refusal(inner).find("registers.statusword.offset: unknown key (expected one of: address, type)"),
            std::string::npos);
  json object = valid_map();
  object["registers"]["torque_demand"] = {{"address", 300}, {"type", "int16"}};
  EXPECT_NE(refusal(object).find("registers.torque_demand: unknown key (expected one of: controlword, statusword,"),
            std::string::npos);
  json limits = valid_map();
  limits["limits"] = {{"acceleration", 3}};
  EXPECT_NE(refusal(limits).find("limits.acceleration: unknown key"), std::string::npos);
  std::string twice = valid_map().dump();
  twice.insert(twice.find("\"controlword\""), R"("controlword": {"address": 300, "type": "uint16"}, )");
  EXPECT_EQ(refusal(twice), "map file x.json: registers.controlword: given twice");
  std::string deep = "{\"format\": " + std::string(20, '[') + std::string(20, ']') + "}";
  EXPECT_EQ(refusal(deep), "map file x.json: nested deeper than 8 levels");
  const std::string deepest = std::string(kMaxMapFileBytes / 2, '[') + std::string(kMaxMapFileBytes / 2, ']');
  EXPECT_EQ(refusal(deepest), "map file x.json: nested deeper than 8 levels");
}

TEST(ModbusMap, MissingObjectsAndSettingsAreRefused) {
  json map = valid_map();
  map["registers"].erase("target_torque");
  EXPECT_EQ(refusal(map), "map file x.json: registers: missing target_torque (0x6071, required)");
  json no_order = valid_map();
  no_order.erase("high_word_first");
  EXPECT_EQ(refusal(no_order), "map file x.json: high_word_first: missing (expected true or false)");
  json no_scale = valid_map();
  no_scale["registers"]["position_actual"].erase("scale");
  EXPECT_EQ(refusal(no_scale),
            "map file x.json: registers.position_actual.scale: missing (expected a finite non-zero number (counts per "
            "metre))");
}

TEST(ModbusMap, AddressesOutOfRangeOrOverlappingAreRefused) {
  json far = valid_map();
  far["registers"]["statusword"]["address"] = 70000;
  EXPECT_EQ(refusal(far), "map file x.json: registers.statusword.address: expected a register address 0..65535, got 70000");
  json negative = valid_map();
  negative["registers"]["statusword"]["address"] = -1;
  EXPECT_NE(refusal(negative).find("registers.statusword.address: expected a register address 0..65535, got -1"),
            std::string::npos);
  json fractional = valid_map();
  fractional["registers"]["statusword"]["address"] = 1.5;
  EXPECT_NE(refusal(fractional).find("registers.statusword.address: expected a register address"), std::string::npos);
  json last = valid_map();
  last["registers"]["target_position"]["address"] = 65535;
  EXPECT_EQ(refusal(last),
            "map file x.json: registers.target_position.address: expected 0..65534 for a 32-bit object (it takes two "
            "registers), got 65535");
  json overlap = valid_map();
  overlap["registers"]["target_velocity"]["address"] = 203;
  EXPECT_EQ(refusal(overlap),
            "map file x.json: registers.target_velocity: registers 203-204 overlap registers.target_position "
            "(registers 202-203)");
}

TEST(ModbusMap, ScalesMustBeFiniteAndNonZero) {
  const std::string expected =
      "map file x.json: registers.position_actual.scale: expected a finite non-zero number (counts per metre)";
  json zero = valid_map();
  zero["registers"]["position_actual"]["scale"] = 0;
  EXPECT_EQ(refusal(zero), expected);
  // JSON has no infinity: a number too large for a double is refused as it is read.
  std::string infinite = valid_map().dump();
  infinite.replace(infinite.find("1000000.0"), 9, "1e400");  // the first scale: position_actual's
  EXPECT_NE(refusal(infinite).find("map file x.json: not valid JSON: "), std::string::npos);
  EXPECT_NE(refusal(infinite).find("number overflow parsing '1e400'"), std::string::npos);
  json text = valid_map();
  text["registers"]["position_actual"]["scale"] = "NaN";
  EXPECT_EQ(refusal(text), expected + ", got \"NaN\"");
  json on_a_word = valid_map();
  on_a_word["registers"]["controlword"]["scale"] = 2;
  EXPECT_EQ(refusal(on_a_word), "map file x.json: registers.controlword.scale: takes no scale (a CiA 402 word or mode)");
  json deceleration = valid_map();
  deceleration["registers"]["quick_stop_deceleration"] = {{"address", 300}, {"type", "uint32"}, {"scale", -1}};
  EXPECT_EQ(refusal(deceleration),
            "map file x.json: registers.quick_stop_deceleration.scale: expected a finite positive number (drive units "
            "per m/s^2)");
}

TEST(ModbusMap, TypesMustBeKnownAndFitTheObject) {
  json unknown = valid_map();
  unknown["registers"]["target_torque"]["type"] = "float";
  EXPECT_EQ(refusal(unknown),
            "map file x.json: registers.target_torque.type: expected \"uint16\", \"int16\", \"uint32\" or \"int32\", "
            "got \"float\"");
  json word = valid_map();
  word["registers"]["statusword"]["type"] = "int32";
  EXPECT_EQ(refusal(word),
            "map file x.json: registers.statusword.type: expected \"uint16\" (a CiA 402 word), got \"int32\"");
  json mode = valid_map();
  mode["registers"]["modes_of_operation"]["type"] = "uint32";
  EXPECT_NE(refusal(mode).find("registers.modes_of_operation.type: expected \"int16\" or \"uint16\""), std::string::npos);
}

TEST(ModbusMap, FileSettingsMustHaveTheirForm) {
  json format = valid_map();
  format["format"] = "modbus";
  EXPECT_EQ(refusal(format), "map file x.json: format: expected \"netmc-modbus-map\", got \"modbus\"");
  json version = valid_map();
  version["version"] = 2;
  EXPECT_EQ(refusal(version), "map file x.json: version: expected 1, got 2");
  json unit = valid_map();
  unit["unit_id"] = 256;
  EXPECT_EQ(refusal(unit), "map file x.json: unit_id: expected a unit id 0..255, got 256");
  json order = valid_map();
  order["high_word_first"] = "yes";
  EXPECT_EQ(refusal(order), "map file x.json: high_word_first: expected true or false, got \"yes\"");
  json mode = valid_map();
  mode["job_mode"] = "pp";
  EXPECT_EQ(refusal(mode), "map file x.json: job_mode: expected \"cst\", \"csv\" or \"csp\", got \"pp\"");
}

TEST(ModbusMap, LimitsMustBePositive) {
  const auto limited = [](const json& limits) {
    json map = valid_map();
    map["limits"] = limits;
    return refusal(map);
  };
  EXPECT_EQ(limited({{"command", 0}}),
            "map file x.json: limits.command: expected a positive number (the plant's input unit)");
  EXPECT_EQ(limited({{"velocity_m_s", -1}}), "map file x.json: limits.velocity_m_s: expected a positive number (m/s)");
  EXPECT_EQ(limited({{"slew_per_s", 0}}),
            "map file x.json: limits.slew_per_s: expected a positive number (the plant's input unit per second)");
  EXPECT_EQ(limited({{"position_window_m", {0.2, 0.1}}}),
            "map file x.json: limits.position_window_m: expected [MIN, MAX] in metres with MIN < MAX");
  EXPECT_EQ(limited({{"position_window_m", 0.2}}),
            "map file x.json: limits.position_window_m: expected [MIN, MAX] in metres with MIN < MAX");
}

TEST(ModbusMap, AnOversizeOrMissingFileIsRefused) {
  std::string big = valid_map().dump();
  big.insert(big.size() - 1, std::string(kMaxMapFileBytes, ' '));
  EXPECT_EQ(refusal(big), "map file x.json: larger than 65536 bytes");
  const std::string path = ::testing::TempDir() + "netmc-oversize-map.json";
  std::ofstream(path) << big;
  try {
    load_modbus_map(path);
    ADD_FAILURE() << "an oversize file was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_EQ(std::string(error.what()), "map file " + path + ": larger than 65536 bytes");
  }
  std::remove(path.c_str());
  try {
    load_modbus_map(path);
    ADD_FAILURE() << "a missing file was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_EQ(std::string(error.what()), "map file " + path + ": cannot read it (No such file or directory)");
  }
}

TEST(ModbusMap, ValuesRoundTripThroughTheirWordsInEitherWordOrder) {
  for (const bool high_first : {true, false}) {
    ModbusMap map = default_modbus_map();
    map.high_word_first = high_first;
    std::array<std::uint16_t, 2> words{};
    for (const double position : {0.0, 0.123456789, -0.5, 2.147483647, -2.147483648}) {
      ASSERT_EQ(map.to_words(DriveObject::target_position, position, words), 2);
      EXPECT_NEAR(map.from_words(DriveObject::target_position, words.data()), position, 0.5e-9);
    }
    // 0x12345678 counts: the word order as the file says.
    map.to_words(DriveObject::position_actual, 0x12345678 * 1e-9, words);
    EXPECT_EQ(words[0], high_first ? 0x1234 : 0x5678);
    EXPECT_EQ(words[1], high_first ? 0x5678 : 0x1234);
    map.to_words(DriveObject::quick_stop_deceleration, 4000.0, words);  // beyond int32, within uint32
    EXPECT_DOUBLE_EQ(map.from_words(DriveObject::quick_stop_deceleration, words.data()), 4000.0);
    EXPECT_EQ(map.to_words(DriveObject::modes_of_operation, -1, words), 1);
    EXPECT_EQ(words[0], 0xFFFF);
    EXPECT_EQ(map.from_words(DriveObject::modes_of_operation, words.data()), -1.0);
    map.to_words(DriveObject::statusword, 0x8637, words);
    EXPECT_EQ(map.from_words(DriveObject::statusword, words.data()), 0x8637);
  }
  // A negative scale turns the direction round.
  ModbusMap map = parse_modbus_map(valid_map().dump(), "map file x.json");
  std::array<std::uint16_t, 2> words{};
  map.to_words(DriveObject::target_velocity, 0.25, words);
  EXPECT_EQ(static_cast<std::int32_t>(static_cast<std::uint32_t>(words[1]) << 16 | words[0]), -250);
  EXPECT_EQ(map.from_words(DriveObject::target_velocity, words.data()), 0.25);
}

TEST(ModbusMap, ValuesThatDoNotFitTheirRegisterAreRefusedNamingObjectValueAndRange) {
  const ModbusMap map = default_modbus_map();
  std::array<std::uint16_t, 2> words{};
  try {
    map.to_words(DriveObject::target_position, 3.0, words);
    ADD_FAILURE() << "3 m fitted an int32 of nanometres";
  } catch (const std::out_of_range& error) {
    EXPECT_EQ(std::string(error.what()),
              "target_position: 3 m does not fit int32 at 1e+09 counts per metre (range -2.14748 to 2.14748 m)");
  }
  EXPECT_THROW(map.to_words(DriveObject::quick_stop_deceleration, -1.0, words), std::out_of_range);
  EXPECT_THROW(map.to_words(DriveObject::target_torque, std::numeric_limits<double>::quiet_NaN(), words),
               std::out_of_range);
  EXPECT_THROW(map.to_words(DriveObject::target_torque, std::numeric_limits<double>::infinity(), words),
               std::out_of_range);
  try {
    map.to_words(DriveObject::controlword, 70000, words);
    ADD_FAILURE() << "70000 fitted a uint16";
  } catch (const std::out_of_range& error) {
    EXPECT_EQ(std::string(error.what()), "controlword: 70000 does not fit uint16 (0 to 65535)");
  }
}

}  // namespace
}  // namespace netmc::drive::modbus
