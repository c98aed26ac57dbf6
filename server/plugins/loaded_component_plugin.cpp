#include "server/plugins/loaded_component_plugin.hpp"

#include <dlfcn.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <limits>
#include <map>
#include <mutex>
#include <stdexcept>
#include <utility>

#include "control/plugin/component_plugin.hpp"
#include "server/plugins/component_plugin_compatibility.hpp"
#include "server/plugins/component_plugin_text.hpp"
#include "server/plugins/plugin_components.hpp"

namespace netmc::plugins {
namespace {

static_assert(std::is_same_v<PluginSettings, control::ComponentSettings>);

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
  throw std::invalid_argument("plugin " + path + ": " + why);
}

// The file as named, checked before the dynamic loader sees it (its own messages do not say
// which of missing, unreadable or not an object it was).
struct stat check_file(const std::string& path) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) refuse(path, "cannot read it: " + std::string(std::strerror(errno)));
  if (!S_ISREG(status.st_mode)) refuse(path, "not a regular file");
  if (::access(path.c_str(), R_OK) != 0) refuse(path, "cannot read it: " + std::string(std::strerror(errno)));
  return status;
}

// Which file a path was when this process mapped it. The dynamic loader hands back the library
// it already has under a name, whatever is on disk now: a plugin rebuilt while its old build is
// still mapped (objects of it alive, or a library that cannot be unloaded) would otherwise run
// the old code without a word.
struct FileIdentity {
  dev_t device;
  ino_t inode;
  timespec modified;
  bool same_as(const FileIdentity& other) const {
    return device == other.device && inode == other.inode && modified.tv_sec == other.modified.tv_sec &&
           modified.tv_nsec == other.modified.tv_nsec;
  }
};

FileIdentity identity_of(const struct stat& status) { return {status.st_dev, status.st_ino, status.st_mtim}; }

std::mutex mapped_files_mutex;
std::map<std::string, FileIdentity>& mapped_files() {  // load path -> the file it was when mapped
  static std::map<std::string, FileIdentity> files;
  return files;
}

// Runs one of the plugin's functions; what it throws comes back as "plugin PATH: MESSAGE".
template <typename Call>
auto call_plugin(const std::string& path, const char* function, Call&& call) -> decltype(call()) {
  try {
    return call();
  } catch (const std::exception& error) {
    refuse(path, plugin_text(error.what(), std::numeric_limits<std::size_t>::max(), "(an exception without a message)"));
  } catch (...) {
    refuse(path, std::string(function) + " threw something that is not a std::exception");
  }
}

}  // namespace

void LoadedComponentPlugin::LibraryCloser::operator()(void* library) const { ::dlclose(library); }

std::shared_ptr<const LoadedComponentPlugin> LoadedComponentPlugin::load(const std::string& path) {
  const FileIdentity file = identity_of(check_file(path));
  // A bare name would send dlopen searching the library path: load the file that was checked.
  const std::string load_path = path.find('/') == std::string::npos ? "./" + path : path;
  Library library;
  {
    const std::lock_guard<std::mutex> lock(mapped_files_mutex);
    const auto known = mapped_files().find(load_path);
    if (void* mapped = ::dlopen(load_path.c_str(), RTLD_LAZY | RTLD_NOLOAD)) {
      ::dlclose(mapped);
      if (known != mapped_files().end() && !known->second.same_as(file)) {
        refuse(path, "it changed on disk since this process loaded it, and the old build is still loaded (objects "
                     "of it in use, or a library that cannot be unloaded): restart to load the new build");
      }
    }
    library.reset(::dlopen(load_path.c_str(), RTLD_NOW | RTLD_LOCAL));
    if (!library) {
      const char* why = ::dlerror();
      refuse(path, "cannot load it as a shared object: " +
                       (why ? plugin_text(why, std::numeric_limits<std::size_t>::max(), "dlopen failed") : "dlopen failed"));
    }
    mapped_files().insert_or_assign(load_path, file);
  }
  ::dlerror();
  void* symbol = ::dlsym(library.get(), NETMC_COMPONENT_PLUGIN_ENTRY);
  if (symbol == nullptr) {
    refuse(path, "exports no " NETMC_COMPONENT_PLUGIN_ENTRY
                 " (the entry NETMC_COMPONENT_PLUGIN of control/plugin/component_plugin.hpp defines)");
  }
  const auto entry = reinterpret_cast<netmc_component_plugin_entry_function>(symbol);
  const netmc_component_plugin* table = entry();
  if (table == nullptr) refuse(path, NETMC_COMPONENT_PLUGIN_ENTRY " returned no table");
  // The plain C head first: nothing else of the plugin is called unless its build is netmc's.
  if (auto mismatch = component_plugin_mismatch(path, *table)) throw std::invalid_argument(*mismatch);
  if (table->make_axis_controller == nullptr && table->make_plant == nullptr) {
    refuse(path, "it provides nothing: its make_axis_controller and make_plant are both null");
  }
  if (table->describe == nullptr) refuse(path, "its table has no describe (a null pointer)");

  std::shared_ptr<LoadedComponentPlugin> plugin(new LoadedComponentPlugin(std::move(library), table, path));
  plugin->description_ = plugin_text(call_plugin(path, "describe", [table] { return table->describe(); }),
                                     "(no description)");
  return plugin;
}

LoadedComponentPlugin::LoadedComponentPlugin(Library library, const netmc_component_plugin* table, std::string path)
    : library_(std::move(library)), table_(table), path_(std::move(path)) {}

LoadedComponentPlugin::~LoadedComponentPlugin() = default;

bool LoadedComponentPlugin::provides_axis_controller() const { return table_->make_axis_controller != nullptr; }

bool LoadedComponentPlugin::provides_plant() const { return table_->make_plant != nullptr; }

std::unique_ptr<control::AxisController> LoadedComponentPlugin::make_axis_controller(const PluginSettings& settings,
                                                                                     std::size_t axis_index,
                                                                                     double sample_period_s) const {
  if (!provides_axis_controller()) {
    refuse(path_, "it provides no axis controller (its make_axis_controller is null), only a plant");
  }
  auto controller = call_plugin(path_, "make_axis_controller", [&] {
    return table_->make_axis_controller(settings, axis_index, sample_period_s);
  });
  if (!controller) refuse(path_, "make_axis_controller gave no controller");
  return std::make_unique<PluginAxisController>(shared_from_this(), std::move(controller));
}

std::unique_ptr<plant::AxisPlant> LoadedComponentPlugin::make_plant(const PluginSettings& settings,
                                                                    std::size_t axis_index) const {
  if (!provides_plant()) refuse(path_, "it provides no plant (its make_plant is null), only an axis controller");
  auto axis = call_plugin(path_, "make_plant", [&] { return table_->make_plant(settings, axis_index); });
  if (!axis) refuse(path_, "make_plant gave no plant");
  return std::make_unique<PluginAxisPlant>(shared_from_this(), std::move(axis));
}

}  // namespace netmc::plugins
