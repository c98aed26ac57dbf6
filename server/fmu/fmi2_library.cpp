#include "server/fmu/fmi2_library.hpp"

#include <dlfcn.h>

#include <cstring>
#include <stdexcept>
#include <type_traits>

#include "server/fmu/printable_text.hpp"

namespace netmc::plant::fmu {
namespace {

// The loader's last error as printable text.
std::string loader_error() {
  const char* why = ::dlerror();
  return why == nullptr ? "no reason given" : printable_text(why, 300);
}

}  // namespace

Fmi2Library::Fmi2Library(const std::string& binary_path, const std::string& fmu_name, const std::string& entry_name) {
  const auto refuse = [&](const std::string& why) {
    throw std::invalid_argument("fmu " + printable_text(fmu_name) + ": " + entry_name + ": " + why);
  };
  // RTLD_NOW: an unresolved symbol is found here, not in the middle of a run; RTLD_LOCAL: the
  // FMU's symbols do not serve other objects (each FMU exports the same fmi2 names).
  handle_ = ::dlopen(binary_path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle_ == nullptr) refuse("cannot load the binary: " + loader_error());
  const auto find = [&](auto*& function, const char* name) {
    ::dlerror();
    void* symbol = ::dlsym(handle_, name);
    if (symbol == nullptr) {
      ::dlclose(handle_);
      handle_ = nullptr;
      refuse(std::string("the binary lacks ") + name + ", an FMI 2.0 co-simulation function netmc needs");
    }
    // POSIX: a function's address obtained from dlsym may be converted to its type.
    function = reinterpret_cast<std::remove_reference_t<decltype(function)>>(symbol);
  };
  find(functions_.get_types_platform, "fmi2GetTypesPlatform");
  find(functions_.get_version, "fmi2GetVersion");
  find(functions_.instantiate, "fmi2Instantiate");
  find(functions_.free_instance, "fmi2FreeInstance");
  find(functions_.setup_experiment, "fmi2SetupExperiment");
  find(functions_.enter_initialization_mode, "fmi2EnterInitializationMode");
  find(functions_.exit_initialization_mode, "fmi2ExitInitializationMode");
  find(functions_.terminate, "fmi2Terminate");
  find(functions_.reset, "fmi2Reset");
  find(functions_.get_real, "fmi2GetReal");
  find(functions_.set_real, "fmi2SetReal");
  find(functions_.do_step, "fmi2DoStep");
  // FMI 2.0, 2.1.4: "2.0" and the "default" platform of fmi2TypesPlatform.h.
  const char* version = functions_.get_version();
  const char* platform = functions_.get_types_platform();
  const std::string version_text = version ? printable_text(version, 32) : "(null)";
  const std::string platform_text = platform ? printable_text(platform, 32) : "(null)";
  if (version_text.substr(0, 3) != "2.0" || platform_text != "default") {
    ::dlclose(handle_);
    handle_ = nullptr;
    refuse("the binary reports FMI version " + quoted(version_text) + " on platform " + quoted(platform_text) +
           " (expected 2.0 on default)");
  }
}

Fmi2Library::~Fmi2Library() {
  if (handle_ != nullptr && !keep_loaded_) ::dlclose(handle_);
}

}  // namespace netmc::plant::fmu
