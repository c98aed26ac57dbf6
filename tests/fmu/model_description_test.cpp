// modelDescription.xml as netmc reads it: the test FMU's description in full, then one refusal
// per kind of problem.

#include "server/fmu/model_description.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "test_fmu.hpp"

namespace netmc::plant::fmu {
namespace {

using test::message_of;

std::string template_xml() {
  std::ifstream in(NETMC_TEST_FMU_TEMPLATE_XML);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A minimal FMI 2.0 co-simulation description around `variables` and `extra`.
std::string document(const std::string& variables, const std::string& version = "2.0",
                     const std::string& extra = "") {
  return "<?xml version=\"1.0\"?><fmiModelDescription fmiVersion=\"" + version +
         "\" modelName=\"m\" guid=\"{g}\"><CoSimulation modelIdentifier=\"m\"/>" + extra + "<ModelVariables>" +
         variables + "</ModelVariables></fmiModelDescription>";
}

std::string refusal(const std::string& xml) {
  return message_of<std::invalid_argument>([&] { parse_model_description(xml, "t.fmu"); });
}

TEST(ModelDescription, ReadsTheTestFmu) {
  const ModelDescription d = parse_model_description(template_xml(), "seed001_axis.fmu");
  EXPECT_EQ(d.fmi_version, "2.0");
  EXPECT_EQ(d.model_name, "seed001_axis");
  EXPECT_EQ(d.co_simulation.model_identifier, "seed001_axis");
  EXPECT_TRUE(d.co_simulation.can_get_and_set_fmu_state);
  EXPECT_TRUE(d.co_simulation.can_handle_variable_communication_step_size);
  EXPECT_FALSE(d.co_simulation.can_be_instantiated_only_once_per_process);
  EXPECT_FALSE(d.co_simulation.can_serialize_fmu_state);
  ASSERT_TRUE(d.default_step_size_s.has_value());
  EXPECT_EQ(*d.default_step_size_s, 1e-3);
  ASSERT_EQ(d.variables.size(), 11u);
  const ScalarVariable* a2 = d.find("a2");
  ASSERT_NE(a2, nullptr);
  EXPECT_EQ(a2->value_reference, 1u);
  EXPECT_EQ(a2->causality, Causality::parameter);
  EXPECT_EQ(a2->variability, Variability::fixed);
  EXPECT_EQ(a2->initial, Initial::exact);
  EXPECT_EQ(*a2->start, -20.0);
  EXPECT_EQ(a2->unit, "1/s");
  const ScalarVariable* x = d.find("x");
  ASSERT_NE(x, nullptr);
  EXPECT_EQ(x->causality, Causality::output);
  EXPECT_EQ(x->initial, Initial::calculated);
  EXPECT_FALSE(x->start.has_value());
  EXPECT_EQ(d.find("u")->causality, Causality::input);
  EXPECT_EQ(d.find("nope"), nullptr);
}

TEST(ModelDescription, AcceptsFmi20Patches) {
  EXPECT_EQ(parse_model_description(document("", "2.0.4"), "t.fmu").fmi_version, "2.0.4");
}

TEST(ModelDescription, RefusesEachProblemNamingIt) {
  const std::string real = "<Real start=\"1\"/>";
  const std::pair<std::string, std::string> cases[] = {
      {"", "malformed XML"},
      {"<fmiModelDescription", "malformed XML"},
      {std::string("<a/>\0<b/>", 9), "a NUL byte"},
      {"<other/>", "the root element is not <fmiModelDescription>"},
      {"<fmiModelDescription modelName=\"m\" guid=\"g\"/>", "<fmiModelDescription> has no fmiVersion attribute"},
      {document("", "3.0"), "fmiVersion is '3.0': netmc runs FMI 2.0"},
      {document("", "2.0b"), "fmiVersion is '2.0b'"},
      {document("", "2.0."), "fmiVersion is '2.0.'"},
      {"<fmiModelDescription fmiVersion=\"2.0\" modelName=\"m\" guid=\"g\"><ModelVariables/></fmiModelDescription>",
       "no <CoSimulation> element"},
      {document("", "2.0", "<CoSimulation modelIdentifier=\"n\"/>"), "two <CoSimulation> elements"},
      {"<fmiModelDescription fmiVersion=\"2.0\" modelName=\"m\" guid=\"g\"><CoSimulation modelIdentifier=\"../x\"/>"
       "<ModelVariables/></fmiModelDescription>",
       "modelIdentifier '../x' is not a C identifier"},
      {"<fmiModelDescription fmiVersion=\"2.0\" modelName=\"m\" guid=\"g\"><CoSimulation modelIdentifier=\"m\" "
       "canGetAndSetFMUstate=\"maybe\"/><ModelVariables/></fmiModelDescription>",
       "CoSimulation canGetAndSetFMUstate is 'maybe', not true or false"},
      {"<fmiModelDescription fmiVersion=\"2.0\" modelName=\"m\" guid=\"g\"><CoSimulation modelIdentifier=\"m\"/>"
       "</fmiModelDescription>",
       "no <ModelVariables> element"},
      {document("<ScalarVariable valueReference=\"1\">" + real + "</ScalarVariable>"), "a <ScalarVariable> has no name"},
      {document("<ScalarVariable name=\"a\">" + real + "</ScalarVariable>"), "variable 'a' has no valueReference"},
      {document("<ScalarVariable name=\"a\" valueReference=\"-1\">" + real + "</ScalarVariable>"),
       "variable 'a' has valueReference '-1', not an unsigned integer"},
      {document("<ScalarVariable name=\"a\" valueReference=\"1\" causality=\"sideways\">" + real + "</ScalarVariable>"),
       "variable 'a' has causality='sideways', not one FMI 2.0 defines"},
      {document("<ScalarVariable name=\"a\" valueReference=\"1\" variability=\"x\">" + real + "</ScalarVariable>"),
       "variable 'a' has variability='x'"},
      {document("<ScalarVariable name=\"a\" valueReference=\"1\" initial=\"x\">" + real + "</ScalarVariable>"),
       "variable 'a' has initial='x'"},
      {document("<ScalarVariable name=\"a\" valueReference=\"1\"/>"), "variable 'a' has no type element"},
      {document("<ScalarVariable name=\"a\" valueReference=\"1\"><Complex/></ScalarVariable>"),
       "variable 'a' has the type element 'Complex'"},
      {document("<ScalarVariable name=\"a\" valueReference=\"1\"><Real start=\"one\"/></ScalarVariable>"),
       "variable 'a' has the start value 'one', not a number"},
      {document("<ScalarVariable name=\"a\" valueReference=\"1\">" + real +
                "</ScalarVariable><ScalarVariable name=\"a\" valueReference=\"2\">" + real + "</ScalarVariable>"),
       "two variables named 'a'"},
      {document("<ScalarVariable name=\"" + std::string(kMaxVariableNameLength + 1, 'n') + "\" valueReference=\"1\">" +
                real + "</ScalarVariable>"),
       "a variable name is empty or longer than 1024 characters"},
      {document("", "2.0", "<DefaultExperiment stepSize=\"0\"/>"), "DefaultExperiment stepSize '0' is not a positive"},
      {document("", "2.0", "<DefaultExperiment stepSize=\"INF\"/>"), "DefaultExperiment stepSize 'INF'"},
      {document("") + std::string(200, '<'), "malformed XML"},
  };
  for (const auto& [xml, expected] : cases) {
    const std::string message = refusal(xml);
    EXPECT_NE(message.find("fmu t.fmu: modelDescription.xml: "), std::string::npos) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << expected << " -> " << message;
  }
}

TEST(ModelDescription, DeepNestingIsRefusedNotRecursedInto) {
  std::string deep;
  for (int i = 0; i < 100000; ++i) deep += "<a>";
  EXPECT_NE(refusal(document("", "2.0", deep)).find("malformed XML"), std::string::npos);
}

}  // namespace
}  // namespace netmc::plant::fmu
