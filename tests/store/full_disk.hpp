#pragma once
// A disk that fills up on demand, for tests in one process: an SQLite VFS over the default one,
// made the default, whose writes fail with SQLITE_FULL (as on a full file system) while full.

namespace netmc::store::testing {

class FullDisk {
 public:
  FullDisk();   // installs the VFS (once per process; it stays for connections still open)
  ~FullDisk();  // room again
  FullDisk(const FullDisk&) = delete;
  FullDisk& operator=(const FullDisk&) = delete;

  void fill();
  void make_room();
};

}  // namespace netmc::store::testing
