// A component plugin that is wrong in one way, chosen at build time, for the loader's refusals:
//   FAKE_ABI_VERSION=N          its table says plugin ABI N
//   FAKE_NETMC_VERSION="x.y.z"  built against another netmc version
//   FAKE_COMPILER="name", FAKE_COMPILER_MAJOR=N   built with another compiler
//   FAKE_NO_ENTRY               exports no entry function
//   FAKE_PROVIDES_NOTHING       both factories null
//   FAKE_PLANT_ONLY             no make_axis_controller
//   FAKE_FACTORIES_THROW        make_axis_controller throws std::invalid_argument (a long text
//                               with control characters), make_plant throws an int
//   FAKE_FACTORIES_RETURN_NULL  both factories return nothing
// Without any, it is a valid plugin of a zero controller and a resting plant. Every call into it
// but the entry's counts in fake_component_plugin_calls, which the tests read to show that a
// refused plugin is never called.
#include "control/plugin/component_plugin.hpp"

#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>

extern "C" NETMC_COMPONENT_PLUGIN_EXPORT int fake_component_plugin_calls;
int fake_component_plugin_calls = 0;

namespace {

class ZeroController final : public netmc::control::AxisController {
 public:
  void reset(double) override {}
  double command(double, double) const override { return 0.0; }
  void commit(double, double, double, double) override {}
  std::unique_ptr<netmc::control::AxisController> clone() const override {
    return std::make_unique<ZeroController>(*this);
  }
  std::string describe() const override { return "zero"; }
};

class RestingAxis final : public netmc::plant::AxisPlant {
 public:
  void reset(double position, double) override { position_ = position; }
  void advance(double duration_s, double) override { time_ += duration_s; }
  double position() const override { return position_; }
  double velocity() const override { return 0.0; }
  double time() const override { return time_; }
  std::unique_ptr<netmc::plant::AxisPlant> clone() const override { return std::make_unique<RestingAxis>(*this); }
  std::string describe() const override { return "resting"; }

 private:
  double position_ = 0.0;
  double time_ = 0.0;
};

[[maybe_unused]] std::unique_ptr<netmc::control::AxisController> make_controller(
    const netmc::control::ComponentSettings&, std::size_t, double) {
  ++fake_component_plugin_calls;
#if defined(FAKE_FACTORIES_THROW)
  throw std::invalid_argument("gain\x1b[2J out of range\n" + std::string(2000, 'x'));
#elif defined(FAKE_FACTORIES_RETURN_NULL)
  return nullptr;
#else
  return std::make_unique<ZeroController>();
#endif
}

[[maybe_unused]] std::unique_ptr<netmc::plant::AxisPlant> make_plant(const netmc::control::ComponentSettings&,
                                                                    std::size_t) {
  ++fake_component_plugin_calls;
#if defined(FAKE_FACTORIES_THROW)
  throw 42;
#elif defined(FAKE_FACTORIES_RETURN_NULL)
  return nullptr;
#else
  return std::make_unique<RestingAxis>();
#endif
}

std::string describe() {
  ++fake_component_plugin_calls;
  return "fake";
}

template <std::size_t N>
void set_text(char (&field)[N], const char* text) {
  std::size_t i = 0;
  for (; i + 1 < N && text[i] != '\0'; ++i) field[i] = text[i];
  for (; i < N; ++i) field[i] = '\0';
}

netmc_component_plugin fake_table() {
#if defined(FAKE_PROVIDES_NOTHING)
  netmc_component_plugin table = NETMC_COMPONENT_PLUGIN_TABLE(describe, nullptr, nullptr);
#elif defined(FAKE_PLANT_ONLY)
  netmc_component_plugin table = NETMC_COMPONENT_PLUGIN_TABLE(describe, nullptr, make_plant);
#else
  netmc_component_plugin table = NETMC_COMPONENT_PLUGIN_TABLE(describe, make_controller, make_plant);
#endif
#ifdef FAKE_ABI_VERSION
  table.abi_version = FAKE_ABI_VERSION;
#endif
#ifdef FAKE_NETMC_VERSION
  set_text(table.netmc_version, FAKE_NETMC_VERSION);
#endif
#ifdef FAKE_COMPILER
  set_text(table.compiler, FAKE_COMPILER);
  table.compiler_major = FAKE_COMPILER_MAJOR;
#endif
  return table;
}

}  // namespace

#ifdef FAKE_NO_ENTRY
// Something exported, so that the library itself loads.
extern "C" NETMC_COMPONENT_PLUGIN_EXPORT const netmc_component_plugin* netmc_component_plugin_entry_misspelt() {
  static const netmc_component_plugin table = fake_table();
  return &table;
}
#else
extern "C" NETMC_COMPONENT_PLUGIN_EXPORT const netmc_component_plugin* netmc_component_plugin_entry() {
  static const netmc_component_plugin table = fake_table();
  return &table;
}
#endif
