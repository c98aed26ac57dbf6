#pragma once
// One component plugin (control/plugin/component_plugin.hpp), loaded and checked: the loader of
// --controller plugin:PATH.so and --plant plugin:PATH.so.
//
// load() refuses, each with one std::invalid_argument that names the path: a file that is
// missing, unreadable or not a regular file (checked before the dynamic loader sees it); one that
// is not a loadable shared object (the dynamic loader's reason); one without the entry
// function; then, from the table's plain C head and before any other function of the plugin is
// called, another ABI version or table size, another netmc version, compiler, C++ library or C++
// standard, or interface classes of other sizes (component_plugin_compatibility.hpp), a table
// with neither factory, and one without describe. Beyond what the dynamic loader itself runs
// (the library's static constructors), only the entry function, which returns a constant, runs
// before those checks.
//
// Lifetime: a loaded plugin is shared. Everything it makes holds a reference to it (clones too),
// and the library is unloaded when the last of them and of the loader's own references is gone,
// never before: objects of a plugin may outlive the code that asked for them. The dynamic
// loader counts its own references, so a path loaded twice is mapped once. Loading anew per job
// (rather than caching for the process's life) lets a rebuilt plugin take effect at the next job
// once no object of the old one is left; while the old build is still mapped (objects of it
// alive, or a library the dynamic loader cannot unload: a C++ library with a STB_GNU_UNIQUE
// symbol, such as std::to_string brings, stays for the process's life), the dynamic loader would
// hand back the old code under the same path, so a path whose file changed since it was mapped
// is refused instead ("restart to load the new build").
//
// Exceptions a factory throws become std::invalid_argument("plugin PATH: " + what()), the text
// bounded and printable; anything else thrown, likewise with a fixed text. A crash in the plugin
// takes the process down: it runs inside netmc, with netmc's privileges.

#include <cstddef>
#include <memory>
#include <string>

#include "control/axis/axis_controller.hpp"
#include "plant/axis_plant.hpp"
#include "server/plugins/component_plugin_spec.hpp"

struct netmc_component_plugin;

namespace netmc::plugins {

class LoadedComponentPlugin : public std::enable_shared_from_this<LoadedComponentPlugin> {
 public:
  // Throws std::invalid_argument for anything refused (see above).
  static std::shared_ptr<const LoadedComponentPlugin> load(const std::string& path);
  ~LoadedComponentPlugin();
  LoadedComponentPlugin(const LoadedComponentPlugin&) = delete;
  LoadedComponentPlugin& operator=(const LoadedComponentPlugin&) = delete;

  // The path as given.
  const std::string& path() const { return path_; }
  // What the plugin's describe() said, bounded and printable.
  const std::string& description() const { return description_; }
  bool provides_axis_controller() const;
  bool provides_plant() const;

  // The plugin's object for one axis, held with a reference to this plugin. Throws
  // std::invalid_argument when the plugin provides no such factory, when the factory throws (its
  // message) and when it returns nothing.
  std::unique_ptr<control::AxisController> make_axis_controller(const PluginSettings& settings, std::size_t axis_index,
                                                                double sample_period_s) const;
  std::unique_ptr<plant::AxisPlant> make_plant(const PluginSettings& settings, std::size_t axis_index) const;

 private:
  struct LibraryCloser {
    void operator()(void* library) const;
  };
  using Library = std::unique_ptr<void, LibraryCloser>;

  LoadedComponentPlugin(Library library, const netmc_component_plugin* table, std::string path);

  Library library_;  // first in, last out: the code `table_` points into
  const netmc_component_plugin* table_;
  std::string path_;
  std::string description_;
};

}  // namespace netmc::plugins
