#include "server/drive/drive.hpp"

namespace netmc::drive {

const char* operation_mode_name(OperationMode mode) {
  switch (mode) {
    case OperationMode::csp: return "csp";
    case OperationMode::csv: return "csv";
    case OperationMode::cst: return "cst";
  }
  return "?";
}

std::optional<OperationMode> operation_mode_from_name(std::string_view name) {
  for (OperationMode mode : {OperationMode::csp, OperationMode::csv, OperationMode::cst}) {
    if (name == operation_mode_name(mode)) return mode;
  }
  return std::nullopt;
}

std::optional<OperationMode> operation_mode_from_code(std::int64_t code) {
  for (OperationMode mode : {OperationMode::csp, OperationMode::csv, OperationMode::cst}) {
    if (code == static_cast<std::int64_t>(mode)) return mode;
  }
  return std::nullopt;
}

}  // namespace netmc::drive
