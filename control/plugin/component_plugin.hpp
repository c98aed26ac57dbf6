#pragma once
// netmc's component plugin ABI, version 1: a researcher's own per-axis control law
// (netmc::control::AxisController) or plant (netmc::plant::AxisPlant), built as a shared object
// against the installed netmc-dev (find_package(netmc), netmc::control and, when it uses netmc's
// models, netmc::plant) and named on the command line as
//   --controller plugin:PATH.so[:key=value,...]     --plant plugin:PATH.so[:key=value,...]
// by netmc sim, netmc sweep, netmc-server and netmc-axis. The built-in controllers and plants
// implement the same two interfaces; netmc drives a plugin's objects exactly as its own.
//
// Unlike the drive plugin ABI (<netmc/drive_plugin.h>, plain C), C++ crosses this boundary:
// netmc calls the plugin's objects through their vtables, destroys them, and passes std::map and
// std::string both ways. That is sound only when both sides were compiled from the same netmc
// headers by the same compiler against the same C++ library, so the plugin states its build in
// plain C data that netmc reads first.
//
// The contract
// - Entry: the plugin exports one function, netmc_component_plugin_entry (extern "C"), written by
//   NETMC_COMPONENT_PLUGIN(describe, make_axis_controller, make_plant) in one of its sources. It
//   returns a constant table and runs nothing else. netmc reads the table's plain C fields and
//   refuses, before it calls any other function of the plugin:
//     another ABI version or table size (abi_version, table_size and netmc_version stay first,
//       in this order, in every ABI version);
//     another netmc version (NETMC_VERSION: the exact version string);
//     another compiler (its name and major version; the minor version is shown, not compared:
//       a compiler series keeps its C++ ABI);
//     another C++ library (its name, its release and, for libstdc++, the std::string ABI);
//     another C++ standard (__cplusplus), or interface classes, settings or strings of other sizes;
//     a table with neither factory (it provides nothing) or without describe.
//   The message names both builds, e.g.
//     plugin libx.so was built against netmc 0.1.0 (plugin ABI 1, gcc 12.2); this is netmc 0.2.0
//     (plugin ABI 1, gcc 12.2): ...
//   and the remedy is always the same: rebuild the plugin against the netmc that loads it.
// - Settings: the key=value pairs after the path, numbers only, then a job's per-axis parameters
//   over them (the later value of a key wins). A factory throws std::invalid_argument with its
//   own message for a key it does not know or a value it refuses; netmc reports it as
//   "plugin PATH: MESSAGE", the text bounded and reduced to printable ASCII. netmc has checked
//   every key against [A-Za-z0-9_.-] and every value is finite.
// - Factories: make_axis_controller(settings, axis_index, sample_period_s) makes the loop of one
//   axis (0 = X, 1 = Y, 2 = Z) for a sample period h > 0; make_plant(settings, axis_index) one axis
//   of the plant. Either may be null when the plugin has none; a non-null factory returns an
//   object or throws. netmc calls a factory once per axis of a job and resets the object before a
//   run.
// - Lifetime: netmc keeps the library loaded while anything it made lives (clones included)
//   and destroys every object before it unloads the library. Keep no object of the plugin's own
//   beyond that (no thread started by a factory that outlives its object).
// - Threads: netmc calls one object from one thread at a time. Objects of one plugin may live on
//   different threads (the axes of a node, concurrent jobs of a server): keep state in the
//   object, or guard what objects share.
// - Exceptions: a factory's are caught and reported as above. One from reset, command, commit,
//   advance or clone reaches netmc as one from its own objects would (the run fails): keep them
//   for states that cannot go on.
// - Failure of the plugin itself: a plugin runs inside netmc's process, with its privileges;
//   netmc cannot contain it. A crash in it (a bad pointer, an abort, std::terminate) takes the
//   process down: netmc sim or netmc sweep, a server with every job it runs, or an axis node.
//
// Building: C++20, hidden visibility (only the entry is exported), linked with
// -Wl,--exclude-libs,ALL when it links netmc's static libraries; examples/controller_plugin
// (installed to share/netmc/examples/controller_plugin) is a complete starting point.

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <type_traits>

#include "control/axis/axis_controller.hpp"
#include "plant/axis_plant.hpp"

#ifndef NETMC_VERSION
#error "NETMC_VERSION is not defined: link netmc::control from find_package(netmc), which defines it"
#endif

// The ABI this header describes. A plugin's table carries it in abi_version.
#define NETMC_COMPONENT_PLUGIN_ABI 1

// The name of the one function netmc looks up (dlsym).
#define NETMC_COMPONENT_PLUGIN_ENTRY "netmc_component_plugin_entry"

// Marks the entry for export from a plugin built with hidden visibility.
#if defined(__GNUC__) || defined(__clang__)
#define NETMC_COMPONENT_PLUGIN_EXPORT __attribute__((visibility("default")))
#else
#define NETMC_COMPONENT_PLUGIN_EXPORT
#endif

// The compiler, as the translation unit that expands NETMC_COMPONENT_PLUGIN_TABLE sees it
// (clang defines __GNUC__ too, so it is asked first).
#if defined(__clang__)
#define NETMC_COMPONENT_PLUGIN_COMPILER "clang"
#define NETMC_COMPONENT_PLUGIN_COMPILER_MAJOR __clang_major__
#define NETMC_COMPONENT_PLUGIN_COMPILER_MINOR __clang_minor__
#elif defined(__GNUC__)
#define NETMC_COMPONENT_PLUGIN_COMPILER "gcc"
#define NETMC_COMPONENT_PLUGIN_COMPILER_MAJOR __GNUC__
#define NETMC_COMPONENT_PLUGIN_COMPILER_MINOR __GNUC_MINOR__
#else
#error "netmc component plugins are built with GCC or Clang"
#endif

// The C++ library (its macros come with any standard header, <string> above).
#if defined(_GLIBCXX_RELEASE)
#define NETMC_COMPONENT_PLUGIN_CXX_LIBRARY "libstdc++"
#define NETMC_COMPONENT_PLUGIN_CXX_LIBRARY_VERSION _GLIBCXX_RELEASE
#define NETMC_COMPONENT_PLUGIN_CXX_STRING_ABI _GLIBCXX_USE_CXX11_ABI  // 1: the C++11 std::string
#elif defined(_LIBCPP_VERSION)
#define NETMC_COMPONENT_PLUGIN_CXX_LIBRARY "libc++"
#define NETMC_COMPONENT_PLUGIN_CXX_LIBRARY_VERSION _LIBCPP_VERSION
#define NETMC_COMPONENT_PLUGIN_CXX_STRING_ABI 0
#else
#error "netmc component plugins are built against libstdc++ or libc++"
#endif

// Sizes of the text fields below, NUL included.
#define NETMC_COMPONENT_PLUGIN_VERSION_SIZE 32
#define NETMC_COMPONENT_PLUGIN_NAME_SIZE 16

namespace netmc::control {

// The key=value settings a factory receives: key -> value.
using ComponentSettings = std::map<std::string, double>;

}  // namespace netmc::control

// What netmc_component_plugin_entry returns. Everything up to `string_size` is plain C data that
// netmc reads and checks before anything else; the functions follow.
struct netmc_component_plugin {
  // First in every ABI version, in this order.
  std::uint32_t abi_version;  // NETMC_COMPONENT_PLUGIN_ABI as the plugin was built
  std::uint32_t table_size;   // sizeof(netmc_component_plugin) as the plugin was built
  char netmc_version[NETMC_COMPONENT_PLUGIN_VERSION_SIZE];  // NETMC_VERSION, NUL-terminated

  // The build, compared with netmc's own.
  char compiler[NETMC_COMPONENT_PLUGIN_NAME_SIZE];  // "gcc" or "clang"
  std::uint32_t compiler_major;
  std::uint32_t compiler_minor;                        // shown, not compared
  char cxx_library[NETMC_COMPONENT_PLUGIN_NAME_SIZE];  // "libstdc++" or "libc++"
  std::uint32_t cxx_library_version;                   // _GLIBCXX_RELEASE or _LIBCPP_VERSION
  std::uint32_t cxx_string_abi;                        // _GLIBCXX_USE_CXX11_ABI (libstdc++), else 0
  std::int64_t cplusplus;                              // __cplusplus
  std::uint32_t axis_controller_size;                  // sizeof(netmc::control::AxisController)
  std::uint32_t axis_plant_size;                       // sizeof(netmc::plant::AxisPlant)
  std::uint32_t settings_size;                         // sizeof(netmc::control::ComponentSettings)
  std::uint32_t string_size;                           // sizeof(std::string)

  // The factories (either may be null, not both) and one line saying what the plugin is.
  std::unique_ptr<netmc::control::AxisController> (*make_axis_controller)(
      const netmc::control::ComponentSettings& settings, std::size_t axis_index, double sample_period_s);
  std::unique_ptr<netmc::plant::AxisPlant> (*make_plant)(const netmc::control::ComponentSettings& settings,
                                                         std::size_t axis_index);
  std::string (*describe)();
};
static_assert(std::is_standard_layout_v<netmc_component_plugin> && std::is_trivially_copyable_v<netmc_component_plugin>,
              "the table is read as plain data");

// The entry function's type, as netmc looks it up.
using netmc_component_plugin_entry_function = const netmc_component_plugin* (*)();

// The table a build makes: its own identification (the macros above, as the translation unit
// that expands this sees them) and the three functions (names of functions, or nullptr).
#define NETMC_COMPONENT_PLUGIN_TABLE(describe_function, axis_controller_factory, plant_factory)             \
  netmc_component_plugin {                                                                                   \
    NETMC_COMPONENT_PLUGIN_ABI, static_cast<std::uint32_t>(sizeof(netmc_component_plugin)), NETMC_VERSION,   \
        NETMC_COMPONENT_PLUGIN_COMPILER, NETMC_COMPONENT_PLUGIN_COMPILER_MAJOR,                              \
        NETMC_COMPONENT_PLUGIN_COMPILER_MINOR, NETMC_COMPONENT_PLUGIN_CXX_LIBRARY,                           \
        NETMC_COMPONENT_PLUGIN_CXX_LIBRARY_VERSION, NETMC_COMPONENT_PLUGIN_CXX_STRING_ABI, __cplusplus,      \
        static_cast<std::uint32_t>(sizeof(netmc::control::AxisController)),                                  \
        static_cast<std::uint32_t>(sizeof(netmc::plant::AxisPlant)),                                         \
        static_cast<std::uint32_t>(sizeof(netmc::control::ComponentSettings)),                               \
        static_cast<std::uint32_t>(sizeof(std::string)), (axis_controller_factory), (plant_factory),         \
        (describe_function)                                                                                  \
  }

// The entry, declared here so that its definition below is checked against it.
extern "C" NETMC_COMPONENT_PLUGIN_EXPORT const netmc_component_plugin* netmc_component_plugin_entry();

// Defines the entry, once per plugin, at namespace scope:
//   NETMC_COMPONENT_PLUGIN(describe, make_pd_loop, nullptr)
// with
//   std::string describe();
//   std::unique_ptr<netmc::control::AxisController> make_pd_loop(
//       const netmc::control::ComponentSettings&, std::size_t axis_index, double sample_period_s);
//   std::unique_ptr<netmc::plant::AxisPlant> make_axis(const netmc::control::ComponentSettings&,
//                                                      std::size_t axis_index);
// The table is a constant: calling the entry runs none of the plugin's code.
#define NETMC_COMPONENT_PLUGIN(describe_function, axis_controller_factory, plant_factory)                    \
  extern "C" NETMC_COMPONENT_PLUGIN_EXPORT const netmc_component_plugin* netmc_component_plugin_entry() {    \
    static constexpr netmc_component_plugin netmc_plugin_table =                                             \
        NETMC_COMPONENT_PLUGIN_TABLE(describe_function, axis_controller_factory, plant_factory);             \
    return &netmc_plugin_table;                                                                              \
  }
