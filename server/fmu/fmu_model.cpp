#include "server/fmu/fmu_model.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "server/fmu/fmu_archive.hpp"
#include "server/fmu/printable_text.hpp"

namespace netmc::plant::fmu {
namespace {

// The memory callbacks (FMI 2.0, 2.1.5: allocateMemory returns zeroed memory, like calloc).
void* allocate_memory(std::size_t count, std::size_t size) { return std::calloc(count, size); }
void free_memory(void* memory) { std::free(memory); }

// A file: URI of an absolute path (RFC 3986: unreserved characters and '/' as they are, every
// other byte percent-encoded).
std::string file_uri(const std::string& path) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string uri = "file://";
  for (const char c : path) {
    const bool plain = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' ||
                       c == '.' || c == '_' || c == '~' || c == '/';
    if (plain) {
      uri.push_back(c);
    } else {
      const auto byte = static_cast<unsigned char>(c);
      uri += {'%', kHex[byte >> 4], kHex[byte & 0x0F]};
    }
  }
  return uri;
}

}  // namespace

FmuModel::FmuModel(std::string path) : path_(std::move(path)), logger_(path_) {}

FmuModel::~FmuModel() = default;

ModelDescription FmuModel::read_description(const std::string& path) {
  const FmuArchive archive(path);
  return parse_model_description(archive.read_model_description(), path);
}

std::shared_ptr<FmuModel> FmuModel::load(const std::string& path) {
  const FmuArchive archive(path);
  std::shared_ptr<FmuModel> model(new FmuModel(path));
  model->description_ = parse_model_description(archive.read_model_description(), path);
  model->directory_ = std::make_unique<PrivateDirectory>();
  // Names netmc chooses: nothing of the archive becomes a path.
  const std::string binary = model->directory_->entry("model.so");
  const std::string& identifier = model->description_.co_simulation.model_identifier;
  archive.extract_linux64_binary(identifier, binary);
  // FMI 2.0, 2.1.5: fmuResourceLocation names the unpacked resources/ directory. netmc unpacks
  // no resources (only the description and the binary); the FMU gets an empty directory.
  const std::string resources = model->directory_->entry("resources");
  if (::mkdir(resources.c_str(), 0700) != 0) {
    throw std::runtime_error("fmu " + printable_text(path) + ": cannot make " + resources + ": " + std::strerror(errno));
  }
  model->resource_location_ = file_uri(resources);
  model->callbacks_.logger = &FmuLogger::log;
  model->callbacks_.allocateMemory = &allocate_memory;
  model->callbacks_.freeMemory = &free_memory;
  model->callbacks_.stepFinished = nullptr;  // fmi2DoStep is never asked to run asynchronously
  model->callbacks_.componentEnvironment = &model->logger_;
  model->library_ = std::make_unique<Fmi2Library>(binary, path, linux64_binary_entry(identifier));
  return model;
}

std::unique_lock<std::mutex> FmuModel::begin_instantiation() {
  std::unique_lock lock(instantiation_mutex_);
  if (fatal()) {
    throw std::runtime_error("fmu " + printable_text(path_) +
                             ": an earlier call returned fmi2Fatal; no instance of this model can be made");
  }
  if (description_.co_simulation.can_be_instantiated_only_once_per_process && live_instances_.load() > 0) {
    throw std::runtime_error("fmu " + printable_text(path_) +
                             ": the model declares canBeInstantiatedOnlyOncePerProcess and one instance lives");
  }
  ++live_instances_;
  return lock;
}

void FmuModel::instance_freed() { --live_instances_; }

void FmuModel::mark_fatal() {
  fatal_.store(true);
  library_->keep_loaded();
}

}  // namespace netmc::plant::fmu
