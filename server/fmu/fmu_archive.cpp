#include "server/fmu/fmu_archive.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zip.h>

#include <cerrno>
#include <cstring>
#include <set>
#include <stdexcept>
#include <vector>

#include "server/fmu/printable_text.hpp"

namespace netmc::plant::fmu {
namespace {

constexpr const char* kModelDescription = "modelDescription.xml";
constexpr std::size_t kChunkBytes = 64 * 1024;

std::string zip_error_text(int code) {
  zip_error_t error;
  zip_error_init_with_code(&error, code);
  std::string text = zip_error_strerror(&error);
  zip_error_fini(&error);
  return text;
}

// Unix mode bits of an entry, when the archive was made on Unix (upper half of the external
// attributes, APPNOTE 4.4.15); 0 when unknown.
std::uint32_t unix_mode(::zip* archive, std::uint64_t index) {
  zip_uint8_t system = 0;
  zip_uint32_t attributes = 0;
  if (zip_file_get_external_attributes(archive, index, 0, &system, &attributes) != 0) return 0;
  return system == ZIP_OPSYS_UNIX ? attributes >> 16 : 0;
}

// Closes a file descriptor on every path out.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string linux64_binary_entry(std::string_view model_identifier) {
  return "binaries/linux64/" + std::string(model_identifier) + ".so";
}

FmuArchive::FmuArchive(std::string path) : path_(std::move(path)) {
  struct stat status {};
  if (::stat(path_.c_str(), &status) != 0) refuse(std::string("cannot read it: ") + std::strerror(errno));
  if (!S_ISREG(status.st_mode)) refuse("not a regular file");
  if (static_cast<std::uint64_t>(status.st_size) > kMaxArchiveBytes) {
    refuse("larger than " + std::to_string(kMaxArchiveBytes >> 20) + " MiB");
  }
  int code = 0;
  // Without ZIP_CHECKCONS: it refuses archives common writers make (libarchive's, with data
  // descriptors); what is read is checked anyway (sizes while reading, the CRC at the end).
  archive_ = zip_open(path_.c_str(), ZIP_RDONLY, &code);
  if (archive_ == nullptr) {
    if (code == ZIP_ER_NOZIP) refuse("not a zip archive (an FMU is one)");
    refuse("not a readable zip archive: " + zip_error_text(code));
  }
  const zip_int64_t entries = zip_get_num_entries(archive_, 0);
  if (entries < 0 || static_cast<std::uint64_t>(entries) > kMaxArchiveEntries) {
    zip_discard(archive_);
    archive_ = nullptr;
    refuse("more than " + std::to_string(kMaxArchiveEntries) + " entries in the archive");
  }
}

FmuArchive::~FmuArchive() {
  if (archive_ != nullptr) zip_discard(archive_);  // read only: nothing to write back
}

void FmuArchive::refuse(const std::string& why) const {
  throw std::invalid_argument("fmu " + printable_text(path_) + ": " + why);
}

std::uint64_t FmuArchive::wanted_entry(const std::string& name, std::uint64_t max_bytes,
                                       const std::string& missing) const {
  const auto entries = static_cast<std::uint64_t>(zip_get_num_entries(archive_, 0));
  std::uint64_t found = entries;
  for (std::uint64_t i = 0; i < entries; ++i) {
    const char* entry = zip_get_name(archive_, i, ZIP_FL_ENC_RAW);
    if (entry == nullptr || name != entry) continue;
    if (found != entries) refuse("two entries named " + name + " in the archive");
    found = i;
  }
  if (found == entries) refuse(missing);
  const std::uint32_t mode = unix_mode(archive_, found);
  if ((mode & S_IFMT) == S_IFLNK) refuse(name + " is a symbolic link");
  if ((mode & S_IFMT) == S_IFDIR) refuse(name + " is a directory");
  zip_stat_t stat;
  zip_stat_init(&stat);
  if (zip_stat_index(archive_, found, 0, &stat) != 0) {
    refuse("cannot read the entry " + name + ": " + zip_strerror(archive_));
  }
  if ((stat.valid & ZIP_STAT_ENCRYPTION_METHOD) && stat.encryption_method != ZIP_EM_NONE) {
    refuse(name + " is encrypted");
  }
  if ((stat.valid & ZIP_STAT_SIZE) && stat.size > max_bytes) {
    refuse(name + " is larger than " + std::to_string(max_bytes) + " bytes");
  }
  return found;
}

template <class Sink>
void FmuArchive::read_entry(std::uint64_t index, const std::string& name, std::uint64_t max_bytes,
                            Sink&& sink) const {
  zip_file_t* file = zip_fopen_index(archive_, index, 0);
  if (file == nullptr) refuse("cannot read the entry " + name + ": " + zip_strerror(archive_));
  struct Closer {
    zip_file_t* file;
    ~Closer() { zip_fclose(file); }
  } closer{file};
  std::vector<char> chunk(kChunkBytes);
  std::uint64_t total = 0;
  for (;;) {
    const zip_int64_t got = zip_fread(file, chunk.data(), chunk.size());
    if (got < 0) refuse("cannot read the entry " + name + ": " + zip_file_strerror(file));
    if (got == 0) break;
    total += static_cast<std::uint64_t>(got);
    // Counted here, whatever the header said: a forged size must not pass.
    if (total > max_bytes) refuse(name + " is larger than " + std::to_string(max_bytes) + " bytes");
    sink(chunk.data(), static_cast<std::size_t>(got));
  }
}

std::string FmuArchive::read_model_description() const {
  const std::uint64_t index =
      wanted_entry(kModelDescription, kMaxModelDescriptionBytes, "no modelDescription.xml in the archive");
  std::string text;
  read_entry(index, kModelDescription, kMaxModelDescriptionBytes,
             [&](const char* data, std::size_t size) { text.append(data, size); });
  return text;
}

std::string FmuArchive::binary_platforms() const {
  constexpr std::size_t kShown = 8;
  std::set<std::string> platforms;
  const auto entries = static_cast<std::uint64_t>(zip_get_num_entries(archive_, 0));
  for (std::uint64_t i = 0; i < entries && platforms.size() < kShown; ++i) {
    const char* entry = zip_get_name(archive_, i, ZIP_FL_ENC_RAW);
    if (entry == nullptr) continue;
    // Files only ("binaries/<platform>/<file>"): an empty directory carries no binary.
    const std::string_view name(entry);
    const std::size_t slash = name.find('/', 9);
    if (name.substr(0, 9) != "binaries/" || slash == std::string_view::npos || slash == 9 ||
        slash + 1 == name.size() || name.back() == '/') {
      continue;
    }
    platforms.insert(printable_text(name.substr(9, slash - 9), 32));
  }
  std::string text;
  for (const auto& platform : platforms) text += (text.empty() ? "" : ", ") + platform;
  return text.empty() ? "none" : text;
}

void FmuArchive::extract_linux64_binary(std::string_view model_identifier, const std::string& destination) const {
  const std::string name = linux64_binary_entry(model_identifier);
  const std::uint64_t index = wanted_entry(
      name, kMaxBinaryBytes, "no " + name + ": no binary for 64-bit Linux (binaries for: " + binary_platforms() + ")");
  // O_EXCL | O_NOFOLLOW: a new file of our own, never one that something else put there.
  Descriptor out{::open(destination.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0700)};
  if (out.fd < 0) {
    throw std::runtime_error("fmu " + printable_text(path_) + ": cannot write " + destination + ": " +
                             std::strerror(errno));
  }
  read_entry(index, name, kMaxBinaryBytes, [&](const char* data, std::size_t size) {
    while (size > 0) {
      const ssize_t written = ::write(out.fd, data, size);
      if (written < 0 && errno == EINTR) continue;
      if (written <= 0) {
        throw std::runtime_error("fmu " + printable_text(path_) + ": cannot write " + destination + ": " +
                                 std::strerror(errno));
      }
      data += written;
      size -= static_cast<std::size_t>(written);
    }
  });
}

}  // namespace netmc::plant::fmu
