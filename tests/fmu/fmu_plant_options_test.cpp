// The `fmu:` options text: what it takes, and one message per malformed option naming its key.

#include "server/fmu/fmu_plant_options.hpp"

#include <gtest/gtest.h>

#include <string>

#include "server/fmu/decimal_number.hpp"
#include "test_fmu.hpp"

namespace netmc::plant::fmu {
namespace {

using test::message_of;

TEST(FmuPlantOptions, TakesEveryKey) {
  const FmuPlantOptions o = parse_fmu_plant_options(
      "fmu:models/axis.fmu:input=cmd,output=pos,velocity=vel,step=250us,position_start=s0,velocity_start=w0,"
      "mass=1.5,y.friction=-2e-3,load[2].m=.5");
  EXPECT_EQ(o.path, "models/axis.fmu");
  EXPECT_EQ(o.input, "cmd");
  EXPECT_EQ(o.output, "pos");
  EXPECT_EQ(o.velocity, "vel");
  EXPECT_DOUBLE_EQ(*o.step_s, 250e-6);
  EXPECT_EQ(o.position_start, "s0");
  EXPECT_EQ(o.velocity_start, "w0");
  ASSERT_EQ(o.parameters.size(), 3u);
  EXPECT_EQ(o.parameters[0].key, "mass");
  EXPECT_EQ(o.parameters[0].value, 1.5);
  EXPECT_EQ(o.parameters[1].key, "y.friction");
  EXPECT_EQ(o.parameters[1].value, -2e-3);
  EXPECT_EQ(o.parameters[2].key, "load[2].m");
  EXPECT_EQ(o.parameters[2].value, 0.5);
}

TEST(FmuPlantOptions, APathAloneLeavesTheDefaults) {
  const FmuPlantOptions o = parse_fmu_plant_options("/abs/path/m.fmu");
  EXPECT_EQ(o.path, "/abs/path/m.fmu");
  EXPECT_FALSE(o.input || o.output || o.velocity || o.step_s || o.position_start || o.velocity_start);
  EXPECT_TRUE(o.parameters.empty());
}

TEST(FmuPlantOptions, RefusesEachMalformedOptionNamingIt) {
  const std::pair<const char*, const char*> cases[] = {
      {"", "no path"},
      {":b=1", "no path"},
      {"model.zip", "does not end in .fmu"},
      {"dir:x/model.fmu", "the path 'dir' does not end in .fmu"},
      {"m.fmu:", "nothing after ':'"},
      {"m.fmu:b=1,,a2=2", "an empty option"},
      {"m.fmu:b=1,", "an empty option"},
      {"m.fmu:b", "option 'b' has no '='"},
      {"m.fmu:=1", "the key is empty"},
      {"m.fmu:b=", "option 'b' has no value"},
      {"m.fmu:b=1,b=2", "option 'b' is given twice"},
      {"m.fmu:b-c=1", "the key 'b-c' has a character other than"},
      {"m.fmu:b=inf", "option 'b': 'inf' is not a finite decimal number"},
      {"m.fmu:b=nan", "option 'b': 'nan' is not a finite decimal number"},
      {"m.fmu:b=1e999", "option 'b': '1e999' is not a finite decimal number"},
      {"m.fmu:b=0x10", "option 'b': '0x10' is not a finite decimal number"},
      {"m.fmu:b= 1", "option 'b': ' 1' is not a finite decimal number"},
      {"m.fmu:b=1.5.2", "option 'b'"},
      {"m.fmu:step=1", "option 'step': '1' is not a positive duration"},
      {"m.fmu:step=0ms", "option 'step': '0ms' is not a positive duration"},
      {"m.fmu:step=-1ms", "option 'step'"},
      {"m.fmu:step=1min", "option 'step'"},
      {"m.fmu:input=a b", "option 'input': the variable name 'a b' has a character other than"},
      {"m.fmu:output=", "option 'output' has no value"},
  };
  for (const auto& [text, expected] : cases) {
    const std::string message = message_of<std::invalid_argument>([&] { parse_fmu_plant_options(text); });
    EXPECT_NE(message.find(expected), std::string::npos) << text << " -> " << message;
  }
  const std::string long_key = "m.fmu:" + std::string(kMaxFmuKeyLength + 1, 'k') + "=1";
  EXPECT_NE(message_of<std::invalid_argument>([&] { parse_fmu_plant_options(long_key); }).find("longer than"),
            std::string::npos);
  std::string many = "m.fmu:";
  for (std::size_t i = 0; i <= kMaxFmuOptions; ++i) many += (i ? ",p" : "p") + std::to_string(i) + "=1";
  EXPECT_NE(message_of<std::invalid_argument>([&] { parse_fmu_plant_options(many); }).find("more than 256 options"),
            std::string::npos);
  EXPECT_THROW(parse_fmu_plant_options(std::string(kMaxFmuOptionsText + 1, 'a')), std::invalid_argument);
}

TEST(FmuPlantOptions, DurationsAndNumbers) {
  EXPECT_DOUBLE_EQ(*parse_fmu_duration("1ms"), 1e-3);
  EXPECT_DOUBLE_EQ(*parse_fmu_duration("0.002s"), 2e-3);
  EXPECT_DOUBLE_EQ(*parse_fmu_duration("250us"), 250e-6);
  EXPECT_DOUBLE_EQ(*parse_fmu_duration("500ns"), 500e-9);
  for (const char* bad : {"", "ms", "1", "1 ms", "-1ms", "0s", "infs", "1e999s", "1e-400s"}) {
    EXPECT_FALSE(parse_fmu_duration(bad).has_value()) << bad;
  }
  EXPECT_EQ(*parse_finite_decimal("-1.25e-3"), -1.25e-3);
  EXPECT_EQ(*parse_finite_decimal("+.5"), 0.5);
  EXPECT_EQ(*parse_finite_decimal("5."), 5.0);
  for (const char* bad : {"", ".", "-", "e5", "1e", "1e+", "0x1p3", "1,5", "1_0", "--1", "1e999"}) {
    EXPECT_FALSE(parse_finite_decimal(bad).has_value()) << bad;
  }
  EXPECT_EQ(*parse_xml_unsigned(" 4294967295 "), 4294967295u);
  EXPECT_FALSE(parse_xml_unsigned("4294967296").has_value());
  EXPECT_FALSE(parse_xml_unsigned("-1").has_value());
  EXPECT_TRUE(std::isinf(*parse_xml_double("-INF")));
  EXPECT_TRUE(*parse_xml_boolean(" 1"));
  EXPECT_FALSE(parse_xml_boolean("yes").has_value());
}

}  // namespace
}  // namespace netmc::plant::fmu
