#pragma once
// A fault netmc-drive-emulator injects on purpose (--fail-after DURATION:KIND), so that a
// master's error handling can be tested deterministically: from DURATION after the first master
// connects, every request is answered with Modbus exception 4 (exception), answered for another
// unit id (wrong-unit), or not answered at all with the connection kept open (silence). A request
// met with an exception or silence does not reach the drive, nor feed its watchdog.

#include <string>

namespace netmc::drive::emulator {

struct InjectedFault {
  enum class Kind { exception, wrong_unit, silence, slow, frozen };
  double after_s = 0.0;
  Kind kind = Kind::exception;
  double delay_s = 0.0;  // slow: how late every answer is

  std::string describe() const;  // "exception from 200 ms after the first connection"
};

const char* injected_fault_kind_name(InjectedFault::Kind kind);  // "wrong-unit"
// Throws std::invalid_argument naming --fail-after and the expected form.
InjectedFault parse_injected_fault(const std::string& text);

}  // namespace netmc::drive::emulator
