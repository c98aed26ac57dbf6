#pragma once
// An FMU file read as the zip archive it is (FMI 2.0, 2.3: modelDescription.xml at the top,
// binaries/<platform>/<modelIdentifier>.so for the shared object). The archive is untrusted:
//   - it is opened only when it is a regular file of at most kMaxArchiveBytes with at most
//     kMaxArchiveEntries entries;
//   - only two entries are ever read, found by their exact names: modelDescription.xml (into
//     memory, at most kMaxModelDescriptionBytes) and the linux64 binary (into a file the caller
//     names, at most kMaxBinaryBytes); an entry name never becomes a path;
//   - a wanted entry that is a symbolic link, a directory, encrypted, named twice, larger than
//     its bound (counted while reading, not trusted from the header) or corrupt (CRC) is refused.
// Every refusal is one std::invalid_argument "fmu PATH: what is wrong".

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

struct zip;  // libzip's archive (zip_t)

namespace netmc::plant::fmu {

inline constexpr std::uint64_t kMaxArchiveBytes = 1ULL << 30;
inline constexpr std::uint64_t kMaxArchiveEntries = 10000;
inline constexpr std::uint64_t kMaxModelDescriptionBytes = 4ULL << 20;
inline constexpr std::uint64_t kMaxBinaryBytes = 64ULL << 20;

// "binaries/linux64/<modelIdentifier>.so", FMI 2.0, 2.3.
std::string linux64_binary_entry(std::string_view model_identifier);

class FmuArchive {
 public:
  explicit FmuArchive(std::string path);
  ~FmuArchive();
  FmuArchive(const FmuArchive&) = delete;
  FmuArchive& operator=(const FmuArchive&) = delete;

  const std::string& path() const { return path_; }
  // The text of modelDescription.xml.
  std::string read_model_description() const;
  // Writes binaries/linux64/<model_identifier>.so to `destination` (a new file, mode 0700).
  void extract_linux64_binary(std::string_view model_identifier, const std::string& destination) const;

 private:
  [[noreturn]] void refuse(const std::string& why) const;
  // Index of the one entry named exactly `name`, checked as wanted entries are (see above).
  std::uint64_t wanted_entry(const std::string& name, std::uint64_t max_bytes, const std::string& missing) const;
  // Reads the entry's data in chunks to sink(data, size), at most max_bytes in all.
  template <class Sink>
  void read_entry(std::uint64_t index, const std::string& name, std::uint64_t max_bytes, Sink&& sink) const;
  // The platforms under binaries/ (for the message when linux64 is missing).
  std::string binary_platforms() const;

  std::string path_;
  ::zip* archive_ = nullptr;
};

}  // namespace netmc::plant::fmu
