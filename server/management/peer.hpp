#pragma once
// The other end of a management conversation, as the job service answers it: a network
// connection (Session) or a client inside netmc-server itself (the console). Thread-safe.

#include <string>

#include "idl/management.pb.h"

namespace netmc::management {

class Peer {
 public:
  virtual ~Peer() = default;
  // Queues a response; responses leave in the order of the calls; dropped once closed.
  virtual void send(const netmc::v1::Response& response) = 0;
  // False once the peer is gone (its jobs are then cancelled unless kept).
  virtual bool open() const = 0;
  // Work under way for this peer (a job it submitted, one it watches); each hold() is undone by
  // one release().
  virtual void hold() = 0;
  virtual void release() = 0;
  // Who it is, for the job store and `netmc jobs`: the connection's address, "console", ...
  virtual std::string name() const { return "client"; }
};

}  // namespace netmc::management
