#pragma once
// An FMU's shared object loaded with dlopen and the fmi2 functions netmc calls, each found by its
// standard name (FMI 2.0, 2.1.1: a binary exports "fmi2DoStep", not a prefixed name). A binary
// that cannot be loaded (the dynamic loader's text is given), that lacks one of the functions,
// or that reports another version or platform than FMI 2.0's "default" is refused with one
// std::invalid_argument naming the FMU and what is wrong.

#include <string>

#include "server/fmu/fmi2_api.h"

namespace netmc::plant::fmu {

// The co-simulation functions netmc needs, none null once loaded.
struct Fmi2Functions {
  fmi2GetTypesPlatformTYPE* get_types_platform = nullptr;
  fmi2GetVersionTYPE* get_version = nullptr;
  fmi2InstantiateTYPE* instantiate = nullptr;
  fmi2FreeInstanceTYPE* free_instance = nullptr;
  fmi2SetupExperimentTYPE* setup_experiment = nullptr;
  fmi2EnterInitializationModeTYPE* enter_initialization_mode = nullptr;
  fmi2ExitInitializationModeTYPE* exit_initialization_mode = nullptr;
  fmi2TerminateTYPE* terminate = nullptr;
  fmi2ResetTYPE* reset = nullptr;
  fmi2GetRealTYPE* get_real = nullptr;
  fmi2SetRealTYPE* set_real = nullptr;
  fmi2DoStepTYPE* do_step = nullptr;
};

class Fmi2Library {
 public:
  // binary_path: the extracted file; fmu_name and entry_name name it in messages.
  Fmi2Library(const std::string& binary_path, const std::string& fmu_name, const std::string& entry_name);
  ~Fmi2Library();
  Fmi2Library(const Fmi2Library&) = delete;
  Fmi2Library& operator=(const Fmi2Library&) = delete;

  const Fmi2Functions& functions() const { return functions_; }
  // Leaves the object mapped when this goes (after fmi2Fatal no code of it may run, its
  // destructors included).
  void keep_loaded() { keep_loaded_ = true; }

 private:
  void* handle_ = nullptr;
  Fmi2Functions functions_;
  bool keep_loaded_ = false;
};

}  // namespace netmc::plant::fmu
