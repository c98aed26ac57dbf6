// The text after modbus-tcp: and the durations in it: every field read, every malformed one
// refused naming the field.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "server/drive/modbus/duration_text.hpp"
#include "server/drive/modbus/modbus_tcp_drive.hpp"
#include "server/drive/modbus/modbus_tcp_spec.hpp"

namespace netmc::drive::modbus {
namespace {

std::string refusal(const std::string& text) {
  try {
    parse_modbus_tcp_spec(text);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  ADD_FAILURE() << "accepted: " << text;
  return {};
}

TEST(ModbusTcpSpec, ReadsEveryField) {
  const ModbusTcpSpec spec = parse_modbus_tcp_spec("drive-3.lab:1502,unit=7,map=/etc/netmc/x.json,timeout=20ms");
  EXPECT_EQ(spec.host, "drive-3.lab");
  EXPECT_EQ(spec.port, 1502);
  EXPECT_EQ(spec.unit, 7);
  EXPECT_EQ(spec.map_path, "/etc/netmc/x.json");
  EXPECT_DOUBLE_EQ(spec.timeout_s, 0.02);
  const ModbusTcpSpec plain = parse_modbus_tcp_spec("127.0.0.1:502");
  EXPECT_EQ(plain.host, "127.0.0.1");
  EXPECT_FALSE(plain.unit);
  EXPECT_FALSE(plain.map_path);
  EXPECT_DOUBLE_EQ(plain.timeout_s, kDefaultTimeoutS);
}

TEST(ModbusTcpSpec, RefusesMalformedFieldsNamingThem) {
  EXPECT_EQ(refusal("127.0.0.1"),
            "modbus-tcp:127.0.0.1: address: expected HOST:PORT[,unit=N][,map=FILE][,timeout=DURATION], got "
            "'127.0.0.1'");
  EXPECT_EQ(refusal("127.0.0.1:0"), "modbus-tcp:127.0.0.1:0: port: expected 1..65535, got '0'");
  EXPECT_EQ(refusal("127.0.0.1:65536"), "modbus-tcp:127.0.0.1:65536: port: expected 1..65535, got '65536'");
  EXPECT_EQ(refusal("127.0.0.1:x"), "modbus-tcp:127.0.0.1:x: port: expected 1..65535, got 'x'");
  EXPECT_NE(refusal("::1:502").find(": host: expected an IPv4 address or a host name"), std::string::npos);
  EXPECT_NE(refusal("dri ve:502").find(": host: expected an IPv4 address or a host name"), std::string::npos);
  EXPECT_NE(refusal(":502").find(": host: "), std::string::npos);
  EXPECT_EQ(refusal("h:502,unit=256"), "modbus-tcp:h:502,unit=256: unit: expected 0..255, got '256'");
  EXPECT_EQ(refusal("h:502,unit=-1"), "modbus-tcp:h:502,unit=-1: unit: expected 0..255, got '-1'");
  EXPECT_EQ(refusal("h:502,speed=1"), "modbus-tcp:h:502,speed=1: 'speed=1': expected unit=N, map=FILE or timeout=DURATION");
  EXPECT_EQ(refusal("h:502,unit=1,unit=2"), "modbus-tcp:h:502,unit=1,unit=2: unit: given twice");
  EXPECT_EQ(refusal("h:502,map="), "modbus-tcp:h:502,map=: map: expected the path of a register map file");
  EXPECT_EQ(refusal("h:502,timeout=20"),
            "modbus-tcp:h:502,timeout=20: timeout: expected a duration such as 20ms, 0.5s or 250us, got '20'");
  EXPECT_EQ(refusal("h:502,timeout=100us"), "modbus-tcp:h:502,timeout=100us: timeout: expected 1ms..10s, got '100us'");
  EXPECT_EQ(refusal("h:502,"), "modbus-tcp:h:502,: '': expected unit=N, map=FILE or timeout=DURATION");
  EXPECT_NE(refusal(std::string("h:502\n")).find("printable"), std::string::npos);
}

TEST(ModbusTcpSpec, TheDriveTakesItsUnitFromTheSpecOrTheMapAndItsMapFromTheFile) {
  EXPECT_EQ(ModbusTcpDrive::from_spec("127.0.0.1:1502")->describe(), "modbus-tcp:127.0.0.1:1502 unit 1");
  EXPECT_EQ(ModbusTcpDrive::from_spec("127.0.0.1:15020,unit=9")->describe(), "modbus-tcp:127.0.0.1:15020 unit 9");
  const auto drive = ModbusTcpDrive::from_spec(std::string("127.0.0.1:1502,map=") + NETMC_DEFAULT_MODBUS_MAP);
  EXPECT_EQ(drive->job_mode(), OperationMode::cst);
  EXPECT_FALSE(drive->configured_limits().any());
  EXPECT_FALSE(drive->connected());  // nothing connects before open()
  try {
    ModbusTcpDrive::from_spec("127.0.0.1:1502,map=/nonexistent/map.json");
    ADD_FAILURE() << "a missing map file was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_EQ(std::string(error.what()), "map file /nonexistent/map.json: cannot read it (No such file or directory)");
  }
}

TEST(DurationText, ReadsSecondsMillisecondsAndMicroseconds) {
  EXPECT_DOUBLE_EQ(parse_duration_s("20ms", "f"), 0.02);
  EXPECT_DOUBLE_EQ(parse_duration_s("250us", "f"), 250e-6);
  EXPECT_DOUBLE_EQ(parse_duration_s("1.5s", "f"), 1.5);
  EXPECT_DOUBLE_EQ(parse_duration_s("0", "f"), 0.0);
  for (const char* bad : {"", "ms", "20", "-1ms", "20 ms", "1e999s", "infs", "0x10ms", "20min"}) {
    EXPECT_THROW(parse_duration_s(bad, "--cycle"), std::invalid_argument) << bad;
  }
  EXPECT_EQ(format_duration(0.05), "50 ms");
  EXPECT_EQ(format_duration(180e-6), "180 us");
  EXPECT_EQ(format_duration(1.5), "1.5 s");
}

}  // namespace
}  // namespace netmc::drive::modbus
