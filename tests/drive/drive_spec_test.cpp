// netmc-axis --drive: the three kinds, one spec for every axis or AXIS=SPEC entries, and one
// message naming the flag for everything else.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "server/drive/drive_spec.hpp"

namespace netmc::drive {
namespace {

std::string refusal(const std::vector<std::string>& values) {
  try {
    parse_drive_flags(values, {"x", "y"}, "seed001");
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "accepted";
}

TEST(DriveSpec, ParsesTheThreeKinds) {
  const DriveSpec sim = parse_drive_spec("sim:seed001:load=2,b=19.5");
  EXPECT_EQ(sim.kind, DriveSpec::Kind::simulated);
  EXPECT_EQ(sim.plant(), "seed001");
  ASSERT_EQ(sim.plant_overrides().size(), 2u);
  EXPECT_EQ(sim.plant_overrides()[1].first, "b");
  EXPECT_EQ(sim.plant_overrides()[1].second, 19.5);
  EXPECT_EQ(parse_drive_spec("modbus-tcp:127.0.0.1:1502,unit=3").kind, DriveSpec::Kind::modbus_tcp);
  EXPECT_EQ(parse_drive_spec("plugin:/opt/lab/ethercat.so:slave=1").text, "/opt/lab/ethercat.so:slave=1");
  EXPECT_EQ(parse_drive_spec("modbus-tcp:h:1").describe(), "modbus-tcp:h:1");
}

TEST(DriveSpec, EveryAxisGetsOneDrive) {
  auto drives = parse_drive_flags({}, {"x", "y"}, "ballscrew");
  EXPECT_EQ(drives.at("x").describe(), "sim:ballscrew");
  drives = parse_drive_flags({"x=modbus-tcp:127.0.0.1:1502", "y=modbus-tcp:127.0.0.1:1503"}, {"x", "y"}, "seed001");
  EXPECT_EQ(drives.at("y").text, "127.0.0.1:1503");
  drives = parse_drive_flags({"sim:seed001", "y=plugin:/p/a.so:k=v"}, {"x", "y"}, "seed001");
  EXPECT_EQ(drives.at("x").describe(), "sim:seed001");
  EXPECT_EQ(drives.at("y").kind, DriveSpec::Kind::plugin);
}

TEST(DriveSpec, RefusesWhatItCannotServe) {
  EXPECT_NE(refusal({"ethercat:eth0"}).find("--drive: unknown drive 'ethercat:eth0'"), std::string::npos);
  EXPECT_NE(refusal({"modbus-tcp:"}).find("nothing after 'modbus-tcp:'"), std::string::npos);
  EXPECT_NE(refusal({"z=sim:seed001"}).find("'z' is not an axis of this node"), std::string::npos);
  EXPECT_NE(refusal({"x=sim:seed001", "x=sim:seed001"}).find("two drives for axis x"), std::string::npos);
  EXPECT_NE(refusal({"modbus-tcp:127.0.0.1:1502"}).find("serves one axis"), std::string::npos);
  EXPECT_NE(refusal({"sim:seed001:load"}).find("expected KEY=NUMBER"), std::string::npos);
  EXPECT_NE(refusal({"sim:seed001:load=nan"}).find("expected KEY=NUMBER"), std::string::npos);
  EXPECT_NE(refusal({std::string("sim:seed\x01")}).find("printable"), std::string::npos);
  EXPECT_NE(refusal({"sim:seed001", "sim:ballscrew"}).find("got two"), std::string::npos);
}

TEST(DriveSpec, DecimalNumbersOnly) {
  double value = 0.0;
  EXPECT_TRUE(parse_finite_decimal("-1.5e-3", value));
  EXPECT_EQ(value, -1.5e-3);
  EXPECT_FALSE(parse_finite_decimal("0x10", value));
  EXPECT_FALSE(parse_finite_decimal("inf", value));
  EXPECT_FALSE(parse_finite_decimal("1e999", value));
  EXPECT_FALSE(parse_finite_decimal("1.5 ", value));
  EXPECT_FALSE(parse_finite_decimal("", value));
}

}  // namespace
}  // namespace netmc::drive
