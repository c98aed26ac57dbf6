#include "server/fmu/model_description.hpp"

#include <tinyxml2.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "server/fmu/decimal_number.hpp"
#include "server/fmu/printable_text.hpp"

namespace netmc::plant::fmu {
namespace {

template <class Enum, std::size_t N>
using NameTable = std::array<std::pair<std::string_view, Enum>, N>;

constexpr NameTable<Causality, 6> kCausalities{{{"parameter", Causality::parameter},
                                                 {"calculatedParameter", Causality::calculated_parameter},
                                                 {"input", Causality::input},
                                                 {"output", Causality::output},
                                                 {"local", Causality::local},
                                                 {"independent", Causality::independent}}};
constexpr NameTable<Variability, 5> kVariabilities{{{"constant", Variability::constant},
                                                     {"fixed", Variability::fixed},
                                                     {"tunable", Variability::tunable},
                                                     {"discrete", Variability::discrete},
                                                     {"continuous", Variability::continuous}}};
constexpr NameTable<Initial, 3> kInitials{
    {{"exact", Initial::exact}, {"approx", Initial::approx}, {"calculated", Initial::calculated}}};
constexpr NameTable<VariableType, 5> kTypes{{{"Real", VariableType::real},
                                              {"Integer", VariableType::integer},
                                              {"Boolean", VariableType::boolean},
                                              {"String", VariableType::string},
                                              {"Enumeration", VariableType::enumeration}}};

template <class Enum, std::size_t N>
std::string_view name_of(const NameTable<Enum, N>& table, Enum value) {
  for (const auto& [name, entry] : table) {
    if (entry == value) return name;
  }
  return "?";
}

// Reads one modelDescription.xml; every method throws through fail().
class DescriptionReader {
 public:
  explicit DescriptionReader(std::string_view fmu_name) : fmu_name_(fmu_name) {}

  [[noreturn]] void fail(const std::string& why) const {
    throw std::invalid_argument("fmu " + printable_text(fmu_name_) + ": modelDescription.xml: " + why);
  }

  ModelDescription read(std::string_view xml) {
    if (xml.find('\0') != std::string_view::npos) fail("malformed XML: a NUL byte in the text");
    tinyxml2::XMLDocument document;
    if (document.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS) {
      fail("malformed XML: " + printable_text(document.ErrorStr() ? document.ErrorStr() : "parse error"));
    }
    const tinyxml2::XMLElement* root = document.RootElement();
    if (root == nullptr || std::string_view(root->Name()) != "fmiModelDescription") {
      fail("the root element is not <fmiModelDescription>");
    }
    ModelDescription out;
    out.fmi_version = required_attribute(*root, "fmiVersion");
    if (!fmi2_version(out.fmi_version)) {
      fail("fmiVersion is " + quoted(out.fmi_version) + ": netmc runs FMI 2.0 co-simulation FMUs");
    }
    out.model_name = required_attribute(*root, "modelName");
    out.guid = required_attribute(*root, "guid");
    out.co_simulation = co_simulation(*root);
    read_variables(*root, out);
    if (const auto* experiment = unique_child(*root, "DefaultExperiment")) {
      if (const char* step = experiment->Attribute("stepSize")) {
        const auto value = parse_xml_double(step);
        if (!value || !(*value > 0.0) || !std::isfinite(*value)) {
          fail("DefaultExperiment stepSize " + quoted(step) + " is not a positive finite number");
        }
        out.default_step_size_s = *value;
      }
    }
    return out;
  }

 private:
  // "2.0" or "2.0.x" (FMI 2.0, 2.2.1: the version of the standard the FMU follows).
  static bool fmi2_version(std::string_view version) {
    if (version == "2.0") return true;
    if (version.substr(0, 4) != "2.0." || version.size() == 4 || version.size() > 16) return false;
    for (const char c : version.substr(4)) {
      if (c < '0' || c > '9') return false;
    }
    return true;
  }

  std::string required_attribute(const tinyxml2::XMLElement& element, const char* name) const {
    const char* value = element.Attribute(name);
    if (value == nullptr) fail("<" + printable_text(element.Name()) + "> has no " + name + " attribute");
    const std::string_view text(value);
    if (text.size() > kMaxAttributeLength) {
      fail(std::string(name) + " is longer than " + std::to_string(kMaxAttributeLength) + " characters");
    }
    return std::string(text);
  }

  // The one child element `name`, nullptr when absent; two of them are refused.
  const tinyxml2::XMLElement* unique_child(const tinyxml2::XMLElement& parent, const char* name) const {
    const tinyxml2::XMLElement* child = parent.FirstChildElement(name);
    if (child != nullptr && child->NextSiblingElement(name) != nullptr) fail(std::string("two <") + name + "> elements");
    return child;
  }

  bool flag(const tinyxml2::XMLElement& element, const char* name) const {
    const char* value = element.Attribute(name);
    if (value == nullptr) return false;  // FMI 2.0, 4.3.1: every capability defaults to false
    const auto parsed = parse_xml_boolean(value);
    if (!parsed) fail(std::string("CoSimulation ") + name + " is " + quoted(value) + ", not true or false");
    return *parsed;
  }

  CoSimulationInterface co_simulation(const tinyxml2::XMLElement& root) const {
    const tinyxml2::XMLElement* element = unique_child(root, "CoSimulation");
    if (element == nullptr) {
      if (root.FirstChildElement("ModelExchange") != nullptr) {
        fail("model exchange only (no <CoSimulation> element): netmc runs co-simulation FMUs, which carry their "
             "own solver");
      }
      fail("no <CoSimulation> element: netmc runs co-simulation FMUs");
    }
    CoSimulationInterface out;
    out.model_identifier = required_attribute(*element, "modelIdentifier");
    // It names a file of the archive and C symbols: a C identifier (FMI 2.0, 2.2.1).
    bool identifier = !out.model_identifier.empty() && !(out.model_identifier[0] >= '0' && out.model_identifier[0] <= '9');
    for (const char c : out.model_identifier) {
      identifier = identifier && ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_');
    }
    if (!identifier) fail("modelIdentifier " + quoted(out.model_identifier) + " is not a C identifier");
    out.needs_execution_tool = flag(*element, "needsExecutionTool");
    out.can_handle_variable_communication_step_size = flag(*element, "canHandleVariableCommunicationStepSize");
    out.can_interpolate_inputs = flag(*element, "canInterpolateInputs");
    out.can_run_asynchronuously = flag(*element, "canRunAsynchronuously");
    out.can_be_instantiated_only_once_per_process = flag(*element, "canBeInstantiatedOnlyOncePerProcess");
    out.can_not_use_memory_management_functions = flag(*element, "canNotUseMemoryManagementFunctions");
    out.can_get_and_set_fmu_state = flag(*element, "canGetAndSetFMUstate");
    out.can_serialize_fmu_state = flag(*element, "canSerializeFMUstate");
    return out;
  }

  template <class Enum, std::size_t N>
  Enum enumerated(const tinyxml2::XMLElement& element, const char* attribute, const NameTable<Enum, N>& table,
                  Enum absent, const std::string& variable) const {
    const char* value = element.Attribute(attribute);
    if (value == nullptr) return absent;
    for (const auto& [name, entry] : table) {
      if (name == value) return entry;
    }
    fail("variable " + quoted(variable) + " has " + attribute + "=" + quoted(value) + ", not one FMI 2.0 defines");
  }

  ScalarVariable variable(const tinyxml2::XMLElement& element) const {
    ScalarVariable out;
    const char* name = element.Attribute("name");
    if (name == nullptr) fail("a <ScalarVariable> has no name");
    out.name = name;
    if (out.name.empty() || out.name.size() > kMaxVariableNameLength) {
      fail("a variable name is empty or longer than " + std::to_string(kMaxVariableNameLength) + " characters (" +
           quoted(out.name) + ")");
    }
    const char* reference = element.Attribute("valueReference");
    if (reference == nullptr) fail("variable " + quoted(out.name) + " has no valueReference");
    const auto value_reference = parse_xml_unsigned(reference);
    if (!value_reference) fail("variable " + quoted(out.name) + " has valueReference " + quoted(reference) + ", not an unsigned integer");
    out.value_reference = *value_reference;
    out.causality = enumerated(element, "causality", kCausalities, Causality::local, out.name);
    out.variability = enumerated(element, "variability", kVariabilities, Variability::continuous, out.name);
    out.initial = enumerated(element, "initial", kInitials, Initial::none, out.name);
    const tinyxml2::XMLElement* type = element.FirstChildElement();
    if (type == nullptr) fail("variable " + quoted(out.name) + " has no type element (Real, Integer, ...)");
    bool known = false;
    for (const auto& [type_name, entry] : kTypes) {
      if (type_name == type->Name()) {
        out.type = entry;
        known = true;
      }
    }
    if (!known) fail("variable " + quoted(out.name) + " has the type element " + quoted(type->Name()) + ", not one FMI 2.0 defines");
    if (out.type == VariableType::real) {
      if (const char* start = type->Attribute("start")) {
        out.start = parse_xml_double(start);
        if (!out.start) fail("variable " + quoted(out.name) + " has the start value " + quoted(start) + ", not a number");
      }
      if (const char* unit = type->Attribute("unit")) out.unit = printable_text(unit, 64);
    }
    return out;
  }

  void read_variables(const tinyxml2::XMLElement& root, ModelDescription& out) const {
    const tinyxml2::XMLElement* list = unique_child(root, "ModelVariables");
    if (list == nullptr) fail("no <ModelVariables> element");
    for (const auto* element = list->FirstChildElement("ScalarVariable"); element != nullptr;
         element = element->NextSiblingElement("ScalarVariable")) {
      if (out.variables.size() == kMaxVariables) fail("more than " + std::to_string(kMaxVariables) + " variables");
      ScalarVariable v = variable(*element);
      if (!out.index_by_name.emplace(v.name, out.variables.size()).second) {
        fail("two variables named " + quoted(v.name));
      }
      out.variables.push_back(std::move(v));
    }
  }

  std::string_view fmu_name_;
};

}  // namespace

std::string_view causality_name(Causality causality) { return name_of(kCausalities, causality); }
std::string_view variability_name(Variability variability) { return name_of(kVariabilities, variability); }
std::string_view variable_type_name(VariableType type) { return name_of(kTypes, type); }

const ScalarVariable* ModelDescription::find(std::string_view name) const {
  const auto found = index_by_name.find(std::string(name));
  return found == index_by_name.end() ? nullptr : &variables[found->second];
}

ModelDescription parse_model_description(std::string_view xml, std::string_view fmu_name) {
  return DescriptionReader(fmu_name).read(xml);
}

}  // namespace netmc::plant::fmu
