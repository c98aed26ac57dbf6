#pragma once
// One netmc-server per --state-dir: an exclusive advisory lock (flock) on DIR/server.lock, held
// for the server's life and released by the kernel when the process ends, however it ends (so a
// kill -9 leaves no stale lock). The file holds the owner's pid, for the refusal's message. Two
// servers on one store would run the same queued jobs and fail each other's running ones.

#include <filesystem>

namespace netmc::store {

class StateDirectoryLock {
 public:
  // Takes the lock or throws StoreError naming the directory and, when it can be read, the pid
  // of the server that holds it.
  explicit StateDirectoryLock(const std::filesystem::path& directory);
  ~StateDirectoryLock();
  StateDirectoryLock(const StateDirectoryLock&) = delete;
  StateDirectoryLock& operator=(const StateDirectoryLock&) = delete;

  static constexpr const char* kFileName = "server.lock";

 private:
  int fd_ = -1;
};

}  // namespace netmc::store
