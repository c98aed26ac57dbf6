#include "server/fmu/fmu_instance.hpp"

#include <sstream>
#include <stdexcept>

#include "server/fmu/fmu_logger.hpp"
#include "server/fmu/printable_text.hpp"

namespace netmc::plant::fmu {

FmuInstance::FmuInstance(std::shared_ptr<FmuModel> model, std::string instance_name)
    : model_(std::move(model)), name_(std::move(instance_name)) {
  const auto lock = model_->begin_instantiation();
  const ModelDescription& description = model_->description();
  // Not visible (batch mode), logging on: the logger keeps only warnings and errors, bounded.
  component_ = model_->functions().instantiate(name_.c_str(), fmi2CoSimulation, description.guid.c_str(),
                                                model_->resource_location().c_str(), model_->callbacks(),
                                                fmi2False, fmi2True);
  if (component_ == nullptr) {
    model_->instance_freed();
    const std::string said = model_->logger().last_message(name_);
    throw std::runtime_error("fmu " + printable_text(model_->path()) + ": fmi2Instantiate failed" +
                             (said.empty() ? "" : " (the FMU said: " + said + ")"));
  }
}

FmuInstance::~FmuInstance() {
  if (model_->fatal()) return;  // FMI 2.0, 2.1.3: no call after fmi2Fatal, fmi2FreeInstance included
  const auto& f = model_->functions();
  // FMI 2.0, 2.1.5: after fmi2Error only fmi2Reset and fmi2FreeInstance may be called.
  if (initialised_ && !errored_) f.terminate(component_);  // its status changes nothing: the instance goes
  const auto lock = model_->begin_free();
  f.free_instance(component_);
  model_->instance_freed();
}

bool FmuInstance::reset() noexcept {
  if (model_->fatal()) return false;
  const fmi2Status status = model_->functions().reset(component_);
  if (status == fmi2Fatal) model_->mark_fatal();
  if (status != fmi2OK && status != fmi2Warning) return false;
  initialised_ = false;
  errored_ = false;
  return true;
}

void FmuInstance::require_usable(const char* call) const {
  if (model_->fatal()) {
    throw std::runtime_error("fmu " + printable_text(model_->path()) + ": " + call +
                             " not called: an earlier call returned fmi2Fatal");
  }
}

namespace {

// FMI 2.0, 2.1.3: fmi2Warning still means the call did its work.
bool succeeded(fmi2Status status) { return status == fmi2OK || status == fmi2Warning; }

}  // namespace

void FmuInstance::fail(fmi2Status status, const std::string& what, double time_s) {
  if (status == fmi2Fatal) model_->mark_fatal();
  if (status != fmi2Discard) errored_ = true;
  std::ostringstream out;
  out.precision(12);
  out << "fmu " << printable_text(model_->path()) << ": " << what << " failed at t = " << time_s
      << " s: " << fmi2_status_name(status);
  const std::string said = model_->logger().last_message(name_);
  if (!said.empty()) out << " (the FMU said: " << said << ")";
  throw std::runtime_error(out.str());
}

void FmuInstance::setup_experiment(double start_time_s) {
  require_usable("fmi2SetupExperiment");
  const fmi2Status status =
      model_->functions().setup_experiment(component_, fmi2False, 0.0, start_time_s, fmi2False, 0.0);
  if (!succeeded(status)) fail(status, "fmi2SetupExperiment", start_time_s);
  start_time_s_ = start_time_s;
}

void FmuInstance::enter_initialization_mode() {
  require_usable("fmi2EnterInitializationMode");
  const fmi2Status status = model_->functions().enter_initialization_mode(component_);
  if (!succeeded(status)) fail(status, "fmi2EnterInitializationMode", start_time_s_);
  initialised_ = true;  // from here fmi2Terminate is due before fmi2FreeInstance
}

void FmuInstance::exit_initialization_mode() {
  require_usable("fmi2ExitInitializationMode");
  const fmi2Status status = model_->functions().exit_initialization_mode(component_);
  if (!succeeded(status)) fail(status, "fmi2ExitInitializationMode", start_time_s_);
}

void FmuInstance::set_real(const RealVariable& variable, double value, double time_s) {
  require_usable("fmi2SetReal");
  const fmi2ValueReference reference = variable.value_reference;
  const fmi2Status status = model_->functions().set_real(component_, &reference, 1, &value);
  // The message is made only on failure: this runs every control period.
  if (!succeeded(status)) fail(status, "fmi2SetReal(" + printable_text(variable.name) + ")", time_s);
}

double FmuInstance::get_real(const RealVariable& variable, double time_s) {
  require_usable("fmi2GetReal");
  const fmi2ValueReference reference = variable.value_reference;
  double value = 0.0;
  const fmi2Status status = model_->functions().get_real(component_, &reference, 1, &value);
  if (!succeeded(status)) fail(status, "fmi2GetReal(" + printable_text(variable.name) + ")", time_s);
  return value;
}

void FmuInstance::do_step(double time_s, double step_s) {
  require_usable("fmi2DoStep");
  const fmi2Status status = model_->functions().do_step(component_, time_s, step_s, fmi2True);
  if (succeeded(status)) return;
  std::ostringstream what;
  what.precision(12);
  what << "fmi2DoStep (step " << step_s << " s)";
  fail(status, what.str(), time_s);
}

}  // namespace netmc::plant::fmu
