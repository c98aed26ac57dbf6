#include "server/drive/emulator/injected_fault.hpp"

#include <stdexcept>

#include "server/drive/modbus/duration_text.hpp"

namespace netmc::drive::emulator {

const char* injected_fault_kind_name(InjectedFault::Kind kind) {
  switch (kind) {
    case InjectedFault::Kind::exception: return "exception";
    case InjectedFault::Kind::wrong_unit: return "wrong-unit";
    case InjectedFault::Kind::silence: return "silence";
    case InjectedFault::Kind::slow: return "slow";
    case InjectedFault::Kind::frozen: return "frozen";
  }
  return "?";
}

std::string InjectedFault::describe() const {
  const std::string what = std::string(injected_fault_kind_name(kind)) +
                           (kind == Kind::slow ? " (answers " + modbus::format_duration(delay_s) + " late)" : "");
  if (after_s == 0.0) return what + " from the first connection";
  return what + " from " + modbus::format_duration(after_s) + " after the first connection";
}

InjectedFault parse_injected_fault(const std::string& text) {
  const std::size_t colon = text.rfind(':');
  const std::string kind = colon == std::string::npos ? std::string() : text.substr(colon + 1);
  InjectedFault fault;
  if (kind == "exception") {
    fault.kind = InjectedFault::Kind::exception;
  } else if (kind == "wrong-unit") {
    fault.kind = InjectedFault::Kind::wrong_unit;
  } else if (kind == "silence") {
    fault.kind = InjectedFault::Kind::silence;
  } else if (kind == "frozen") {
    fault.kind = InjectedFault::Kind::frozen;
  } else if (kind.rfind("slow=", 0) == 0) {
    fault.kind = InjectedFault::Kind::slow;
    fault.delay_s = modbus::parse_duration_s(kind.substr(5), "--fail-after (slow=DURATION)");
    if (!(fault.delay_s > 0.0 && fault.delay_s <= 10.0)) {
      throw std::invalid_argument("--fail-after: slow=DURATION expects a delay of more than 0 and at most 10 s, got '" +
                                  text.substr(0, 80) + "'");
    }
  } else {
    throw std::invalid_argument("--fail-after: expected DURATION:KIND with KIND exception, wrong-unit, silence, "
                                "slow=DURATION or frozen, got '" +
                                text.substr(0, 80) + "'");
  }
  fault.after_s = modbus::parse_duration_s(text.substr(0, colon), "--fail-after");
  return fault;
}

}  // namespace netmc::drive::emulator
