#pragma once
// A directory only this process's user can enter (mkdtemp, mode 0700) under $TMPDIR (when it is
// an absolute path) or /tmp, for an FMU's unpacked binary: the dynamic loader needs a file.
// Removed with everything in it when the object goes; removal never follows a symbolic link.

#include <string>
#include <string_view>

namespace netmc::plant::fmu {

class PrivateDirectory {
 public:
  // Throws std::runtime_error when no directory can be made (the errno text says why).
  PrivateDirectory();
  ~PrivateDirectory();
  PrivateDirectory(const PrivateDirectory&) = delete;
  PrivateDirectory& operator=(const PrivateDirectory&) = delete;

  const std::string& path() const { return path_; }
  // path()/name, for a name netmc chose (never one taken from an archive).
  std::string entry(std::string_view name) const;

 private:
  std::string path_;
};

}  // namespace netmc::plant::fmu
