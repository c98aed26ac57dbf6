#pragma once
// One FMU loaded for co-simulation: its archive unpacked into a private directory, its
// modelDescription.xml read, its linux64 binary loaded, and the callbacks its instances get. The
// axes of one plant set share one FmuModel (std::shared_ptr), each with instances of its own;
// the directory is removed and the binary unloaded when the last user goes.
//
// The model keeps the FMI 2.0 rules that span instances:
//   - canBeInstantiatedOnlyOncePerProcess (4.3.1): a second live instance is refused;
//   - fmi2Fatal (2.1.3): "the model computations are irreparably corrupted for all FMU
//     instances": after one, no fmi2 function of the model is called again (instances are
//     abandoned, not freed, and the binary stays mapped).

#include <atomic>
#include <cstddef>
#include <memory>
#include <mutex>
#include <string>

#include "server/fmu/fmi2_api.h"
#include "server/fmu/fmi2_library.hpp"
#include "server/fmu/fmu_logger.hpp"
#include "server/fmu/model_description.hpp"
#include "server/fmu/private_directory.hpp"

namespace netmc::plant::fmu {

class FmuModel {
 public:
  // Reads and loads the FMU at `path`. Throws std::invalid_argument naming the FMU and what is
  // wrong with it, std::runtime_error when the machine fails (no temporary directory, disk full).
  static std::shared_ptr<FmuModel> load(const std::string& path);

  // Reads modelDescription.xml only (no unpacking, no loading), for what an FMU offers.
  static ModelDescription read_description(const std::string& path);

  FmuModel(const FmuModel&) = delete;
  FmuModel& operator=(const FmuModel&) = delete;
  ~FmuModel();

  const std::string& path() const { return path_; }
  const ModelDescription& description() const { return description_; }
  const Fmi2Functions& functions() const { return library_->functions(); }
  const fmi2CallbackFunctions* callbacks() const { return &callbacks_; }
  const std::string& resource_location() const { return resource_location_; }
  const FmuLogger& logger() const { return logger_; }

  // Counts a new instance; throws std::runtime_error when the model allows one per process and
  // one lives. Serialises fmi2Instantiate/fmi2FreeInstance across threads (some exporters keep
  // instance lists in globals).
  std::unique_lock<std::mutex> begin_instantiation();
  // Held around fmi2FreeInstance; instance_freed() then uncounts the instance.
  std::unique_lock<std::mutex> begin_free() { return std::unique_lock(instantiation_mutex_); }
  void instance_freed();
  std::size_t live_instances() const { return live_instances_.load(); }

  bool fatal() const { return fatal_.load(); }
  void mark_fatal();

 private:
  explicit FmuModel(std::string path);

  std::string path_;
  std::unique_ptr<PrivateDirectory> directory_;  // declared first: removed last
  ModelDescription description_;
  std::string resource_location_;
  FmuLogger logger_;
  fmi2CallbackFunctions callbacks_{};
  std::unique_ptr<Fmi2Library> library_;
  std::mutex instantiation_mutex_;
  std::atomic<std::size_t> live_instances_{0};
  std::atomic<bool> fatal_{false};
};

}  // namespace netmc::plant::fmu
