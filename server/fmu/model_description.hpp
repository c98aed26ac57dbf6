#pragma once
// What netmc reads of an FMU's modelDescription.xml (FMI 2.0, section 2.2): the version, the
// co-simulation interface with its model identifier and capability flags (section 4.3.1), the
// scalar variables (2.2.7) and the default experiment's step size (2.2.5). The text is untrusted:
// it is bounded (kMaxVariables variables, names of at most kMaxVariableNameLength characters) and
// every problem is one std::invalid_argument "fmu NAME: modelDescription.xml: what is wrong".

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace netmc::plant::fmu {

inline constexpr std::size_t kMaxVariables = 200000;
inline constexpr std::size_t kMaxVariableNameLength = 1024;
inline constexpr std::size_t kMaxAttributeLength = 1024;  // modelIdentifier, modelName, guid

// FMI 2.0, 2.2.7, attributes of a ScalarVariable.
enum class Causality { parameter, calculated_parameter, input, output, local, independent };
enum class Variability { constant, fixed, tunable, discrete, continuous };
enum class Initial { none, exact, approx, calculated };  // none: the attribute is absent
enum class VariableType { real, integer, boolean, string, enumeration };

std::string_view causality_name(Causality causality);
std::string_view variability_name(Variability variability);
std::string_view variable_type_name(VariableType type);

struct ScalarVariable {
  std::string name;
  unsigned int value_reference = 0;
  Causality causality = Causality::local;           // FMI 2.0 default
  Variability variability = Variability::continuous;  // FMI 2.0 default
  Initial initial = Initial::none;
  VariableType type = VariableType::real;
  std::optional<double> start;  // Real start value (may be INF or NaN as xs:double allows)
  std::string unit;             // Real unit attribute, "" when absent
};

// FMI 2.0, 4.3.1: the <CoSimulation> element.
struct CoSimulationInterface {
  std::string model_identifier;
  bool needs_execution_tool = false;
  bool can_handle_variable_communication_step_size = false;
  bool can_interpolate_inputs = false;
  bool can_run_asynchronuously = false;  // the standard's spelling
  bool can_be_instantiated_only_once_per_process = false;
  bool can_not_use_memory_management_functions = false;
  bool can_get_and_set_fmu_state = false;
  bool can_serialize_fmu_state = false;
};

struct ModelDescription {
  std::string fmi_version;
  std::string model_name;
  std::string guid;
  CoSimulationInterface co_simulation;
  std::vector<ScalarVariable> variables;
  std::optional<double> default_step_size_s;

  // The variable named exactly `name`, or nullptr.
  const ScalarVariable* find(std::string_view name) const;

  std::unordered_map<std::string, std::size_t> index_by_name;  // into variables; names are unique
};

// `fmu_name` names the FMU in messages (its path).
ModelDescription parse_model_description(std::string_view xml, std::string_view fmu_name);

}  // namespace netmc::plant::fmu
