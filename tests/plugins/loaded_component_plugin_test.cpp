// What LoadedComponentPlugin::load refuses, each with one message naming the path: a missing
// file, a directory, a file that is not a shared object, a plugin without the entry, one built
// for another ABI, another netmc version or another compiler (naming both builds), one that
// provides nothing; a refused plugin is never called; a plugin rebuilt while its old build is
// still loaded. What a factory throws comes back as
// "plugin PATH: ...", bounded and printable. A plugin's objects keep its library loaded: a clone
// works after the loader and the original are gone, and the library goes with the last object.
#include "server/plugins/loaded_component_plugin.hpp"

#include <dlfcn.h>
#include <unistd.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "control/plugin/component_plugin.hpp"
#include "server/plugins/component_plugin_text.hpp"
#include "server/plugins/plugin_component_factories.hpp"

namespace netmc::plugins {
namespace {

// The message `call` throws std::invalid_argument with ("" if it does not).
template <typename Call>
std::string thrown(Call&& call) {
  try {
    call();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

std::string refusal(const std::string& path) {
  return thrown([&] { LoadedComponentPlugin::load(path); });
}

// "netmc 0.1.0 (plugin ABI 1, gcc 12.2)" for this build.
std::string this_build(const std::string& version = NETMC_VERSION, const std::string& compiler = "") {
  return "netmc " + version + " (plugin ABI 1, " +
         (compiler.empty() ? std::string(NETMC_COMPONENT_PLUGIN_COMPILER) + " " +
                                 std::to_string(NETMC_COMPONENT_PLUGIN_COMPILER_MAJOR) + "." +
                                 std::to_string(NETMC_COMPONENT_PLUGIN_COMPILER_MINOR)
                           : compiler) +
         ")";
}

// A fake plugin's count of calls into it, read through a handle of the test's own (which also
// keeps the library, and so the count, loaded across load()'s dlopen and dlclose).
class CallCount {
 public:
  explicit CallCount(const char* path) : library_(::dlopen(path, RTLD_NOW | RTLD_LOCAL)) {
    if (library_ == nullptr) throw std::runtime_error(::dlerror());
    count_ = static_cast<int*>(::dlsym(library_, "fake_component_plugin_calls"));
    if (count_ == nullptr) throw std::runtime_error("no fake_component_plugin_calls");
  }
  ~CallCount() { ::dlclose(library_); }
  CallCount(const CallCount&) = delete;
  CallCount& operator=(const CallCount&) = delete;
  int calls() const { return *count_; }

 private:
  void* library_;
  int* count_ = nullptr;
};

// True while the library at `path` is mapped in this process.
bool loaded(const char* path) {
  void* library = ::dlopen(path, RTLD_NOW | RTLD_NOLOAD);
  if (library == nullptr) return false;
  ::dlclose(library);
  return true;
}

TEST(LoadedComponentPlugin, RefusesAMissingFileADirectoryAndAFileThatIsNotASharedObject) {
  EXPECT_EQ(refusal("/nonexistent/netmc/libpd.so"),
            "plugin /nonexistent/netmc/libpd.so: cannot read it: No such file or directory");
  EXPECT_EQ(refusal("/tmp"), "plugin /tmp: not a regular file");
  const std::string message = refusal(NETMC_TEST_NOT_A_PLUGIN);
  EXPECT_EQ(message.rfind(std::string("plugin ") + NETMC_TEST_NOT_A_PLUGIN + ": cannot load it as a shared object: ", 0),
            0u)
      << message;
  EXPECT_NE(message.find("invalid ELF header"), std::string::npos) << message;
}

TEST(LoadedComponentPlugin, RefusesAPluginWithoutTheEntry) {
  EXPECT_EQ(refusal(NETMC_TEST_COMPONENT_NO_ENTRY),
            std::string("plugin ") + NETMC_TEST_COMPONENT_NO_ENTRY +
                ": exports no netmc_component_plugin_entry (the entry NETMC_COMPONENT_PLUGIN of "
                "control/plugin/component_plugin.hpp defines)");
}

TEST(LoadedComponentPlugin, RefusesAnotherAbiBeforeCallingIt) {
  CallCount count(NETMC_TEST_COMPONENT_ABI2);
  EXPECT_EQ(refusal(NETMC_TEST_COMPONENT_ABI2), std::string("plugin ") + NETMC_TEST_COMPONENT_ABI2 +
                                                    " was built against netmc " NETMC_VERSION " (plugin ABI 2); this is " +
                                                    this_build() +
                                                    ": another plugin ABI; rebuild the plugin against this netmc");
  EXPECT_EQ(count.calls(), 0);
}

TEST(LoadedComponentPlugin, RefusesAnotherNetmcVersionNamingBothBeforeCallingIt) {
  CallCount count(NETMC_TEST_COMPONENT_VERSION);
  EXPECT_EQ(refusal(NETMC_TEST_COMPONENT_VERSION),
            std::string("plugin ") + NETMC_TEST_COMPONENT_VERSION + " was built against " + this_build("0.0.1") +
                "; this is " + this_build() + ": another netmc version; rebuild the plugin against this netmc");
  EXPECT_EQ(count.calls(), 0);
}

TEST(LoadedComponentPlugin, RefusesAnotherCompilerNamingBothBeforeCallingIt) {
  CallCount count(NETMC_TEST_COMPONENT_COMPILER);
  EXPECT_EQ(refusal(NETMC_TEST_COMPONENT_COMPILER),
            std::string("plugin ") + NETMC_TEST_COMPONENT_COMPILER + " was built against " +
                this_build(NETMC_VERSION, "clang 16." + std::to_string(NETMC_COMPONENT_PLUGIN_COMPILER_MINOR)) +
                "; this is " + this_build() + ": another compiler (clang 16, netmc " NETMC_COMPONENT_PLUGIN_COMPILER " " +
                std::to_string(NETMC_COMPONENT_PLUGIN_COMPILER_MAJOR) + "); rebuild the plugin against this netmc");
  EXPECT_EQ(count.calls(), 0);
}

TEST(LoadedComponentPlugin, RefusesAPluginThatProvidesNothing) {
  CallCount count(NETMC_TEST_COMPONENT_NOTHING);
  EXPECT_EQ(refusal(NETMC_TEST_COMPONENT_NOTHING),
            std::string("plugin ") + NETMC_TEST_COMPONENT_NOTHING +
                ": it provides nothing: its make_axis_controller and make_plant are both null");
  EXPECT_EQ(count.calls(), 0);
}

TEST(LoadedComponentPlugin, AValidPluginIsDescribedAndMakesBothParts) {
  CallCount count(NETMC_TEST_COMPONENT_VALID);
  const auto plugin = LoadedComponentPlugin::load(NETMC_TEST_COMPONENT_VALID);
  EXPECT_EQ(plugin->path(), NETMC_TEST_COMPONENT_VALID);
  EXPECT_EQ(plugin->description(), "fake");
  EXPECT_TRUE(plugin->provides_axis_controller());
  EXPECT_TRUE(plugin->provides_plant());
  EXPECT_EQ(plugin->make_axis_controller({}, 0, 1e-3)->describe(), "zero");
  EXPECT_EQ(plugin->make_plant({}, 1)->describe(), "resting");
  EXPECT_EQ(count.calls(), 3);  // describe and the two factories
}

TEST(LoadedComponentPlugin, AFactorysExceptionComesBackBoundedAndPrintable) {
  const auto plugin = LoadedComponentPlugin::load(NETMC_TEST_COMPONENT_THROWS);
  const std::string prefix = std::string("plugin ") + NETMC_TEST_COMPONENT_THROWS + ": ";
  EXPECT_EQ(thrown([&] { plugin->make_axis_controller({{"kp", 1.0}}, 0, 1e-3); }),
            prefix + "gain?[2J out of range?" + std::string(kMaxPluginTextLength - 22, 'x') + "...");
  EXPECT_EQ(thrown([&] { plugin->make_plant({}, 0); }),
            prefix + "make_plant threw something that is not a std::exception");
}

TEST(LoadedComponentPlugin, RefusesAPartThePluginDoesNotProvideAndAFactoryThatGivesNothing) {
  const auto plant_only = LoadedComponentPlugin::load(NETMC_TEST_COMPONENT_PLANT_ONLY);
  EXPECT_FALSE(plant_only->provides_axis_controller());
  EXPECT_TRUE(plant_only->provides_plant());
  EXPECT_EQ(thrown([&] { plant_only->make_axis_controller({}, 0, 1e-3); }),
            std::string("plugin ") + NETMC_TEST_COMPONENT_PLANT_ONLY +
                ": it provides no axis controller (its make_axis_controller is null), only a plant");
  const auto empty_handed = LoadedComponentPlugin::load(NETMC_TEST_COMPONENT_RETURNS_NULL);
  const std::string prefix = std::string("plugin ") + NETMC_TEST_COMPONENT_RETURNS_NULL + ": ";
  EXPECT_EQ(thrown([&] { empty_handed->make_axis_controller({}, 0, 1e-3); }),
            prefix + "make_axis_controller gave no controller");
  EXPECT_EQ(thrown([&] { empty_handed->make_plant({}, 0); }), prefix + "make_plant gave no plant");
}

TEST(LoadedComponentPlugin, AClonesLibraryStaysLoadedAfterTheLoaderAndTheOriginalAreGone) {
  std::unique_ptr<control::AxisController> copy;
  {
    auto plugin = LoadedComponentPlugin::load(NETMC_TEST_COMPONENT_EXAMPLE);
    auto controller = plugin->make_axis_controller({{"kp", 400.0}, {"kd", 40.0}}, 0, 1e-3);
    plugin.reset();
    copy = controller->clone();
  }
  EXPECT_TRUE(loaded(NETMC_TEST_COMPONENT_EXAMPLE));
  copy->reset(0.0);
  EXPECT_EQ(copy->command(1e-3, 0.0), 400.0 * 1e-3 + 40.0 * 1e-3 / 1e-3);
  copy->commit(1e-3, 0.0, 0.0, 0.0);
  EXPECT_EQ(copy->clone()->command(1e-3, 0.0), 400.0 * 1e-3);
  EXPECT_EQ(copy->describe(), "example pd(kp=400, kd=40)");
}

// The dynamic loader unmaps a library on its last dlclose unless the library cannot be
// unloaded (a C++ library with a STB_GNU_UNIQUE symbol, as the example has through
// std::to_string, stays for the process's life): this fake has none, so the release shows.
TEST(LoadedComponentPlugin, TheLibraryGoesWithTheLastObjectItMade) {
  const char* path = NETMC_TEST_COMPONENT_VALID;
  ASSERT_FALSE(loaded(path));
  std::unique_ptr<control::AxisController> controller;
  std::unique_ptr<plant::AxisPlant> axis;
  {
    const auto plugin = LoadedComponentPlugin::load(path);
    controller = plugin->make_axis_controller({}, 0, 1e-3)->clone();
    axis = plugin->make_plant({}, 0);
  }
  EXPECT_TRUE(loaded(path));
  controller.reset();
  EXPECT_TRUE(loaded(path));
  axis->advance(0.5, 1.0);
  EXPECT_EQ(axis->clone()->time(), 0.5);
  axis.reset();
  EXPECT_FALSE(loaded(path));
}

TEST(LoadedComponentPlugin, APlantSetsAxisKeepsItsLibraryLoaded) {
  const char* path = NETMC_TEST_COMPONENT_VALID;
  ASSERT_FALSE(loaded(path));
  auto set = make_plugin_plant_set(path, 2, {});
  EXPECT_EQ(set.description, std::string("plugin:") + path + " (fake) | X: resting | Y: resting");
  auto axis = std::move(set.axes[1]);
  set = {};
  EXPECT_TRUE(loaded(path));
  axis->advance(0.01, 1.0);
  EXPECT_EQ(axis->time(), 0.01);
  axis.reset();
  EXPECT_FALSE(loaded(path));
}

TEST(LoadedComponentPlugin, RefusesAPluginRebuiltWhileItsOldBuildIsStillLoaded) {
  const std::filesystem::path path =
      std::filesystem::path(testing::TempDir()) / ("libnetmc_rebuilt_plugin_" + std::to_string(::getpid()) + ".so");
  const std::filesystem::path next = path.string() + ".new";
  std::filesystem::copy_file(NETMC_TEST_COMPONENT_VALID, path, std::filesystem::copy_options::overwrite_existing);
  auto axis = LoadedComponentPlugin::load(path)->make_plant({}, 0);  // holds the old build
  // A rebuild: a new file under the same name, as a linker writes one.
  std::filesystem::copy_file(NETMC_TEST_COMPONENT_THROWS, next, std::filesystem::copy_options::overwrite_existing);
  std::filesystem::rename(next, path);
  EXPECT_EQ(refusal(path), "plugin " + path.string() +
                               ": it changed on disk since this process loaded it, and the old build is still loaded "
                               "(objects of it in use, or a library that cannot be unloaded): restart to load the new "
                               "build");
  EXPECT_EQ(axis->describe(), "resting");
  axis.reset();  // the old build goes with its last object
  const auto rebuilt = LoadedComponentPlugin::load(path);
  EXPECT_EQ(thrown([&] { rebuilt->make_plant({}, 0); }),
            "plugin " + path.string() + ": make_plant threw something that is not a std::exception");
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace netmc::plugins
