#include "server/drive/emulator/injected_fault.hpp"

#include <stdexcept>

#include "server/drive/modbus/duration_text.hpp"

namespace netmc::drive::emulator {

const char* injected_fault_kind_name(InjectedFault::Kind kind) {
  switch (kind) {
    case InjectedFault::Kind::exception: return "exception";
    case InjectedFault::Kind::wrong_unit: return "wrong-unit";
    case InjectedFault::Kind::silence: return "silence";
  }
  return "?";
}

std::string InjectedFault::describe() const {
  if (after_s == 0.0) return std::string(injected_fault_kind_name(kind)) + " from the first connection";
  return std::string(injected_fault_kind_name(kind)) + " from " + modbus::format_duration(after_s) +
         " after the first connection";
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
  } else {
    throw std::invalid_argument("--fail-after: expected DURATION:KIND with KIND exception, wrong-unit or silence, got '" +
                                text.substr(0, 80) + "'");
  }
  fault.after_s = modbus::parse_duration_s(text.substr(0, colon), "--fail-after");
  return fault;
}

}  // namespace netmc::drive::emulator
