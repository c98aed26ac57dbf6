#pragma once
// The other end of a management conversation, as the job service answers it: a network
// connection (Session) or a client inside netmc-server itself (the console). Thread-safe.

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
};

}  // namespace netmc::management
