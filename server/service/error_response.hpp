#pragma once
// The management protocol's refusal of one request, shared by the job service's parts.
// See docs/architecture.md, The management protocol.

#include <cstdint>
#include <string>

#include "idl/management.pb.h"

namespace netmc::service {

inline netmc::v1::Response error_response(std::uint64_t request_id, const std::string& message) {
  netmc::v1::Response response;
  response.set_request_id(request_id);
  response.mutable_error()->set_message(message);
  return response;
}

}  // namespace netmc::service
