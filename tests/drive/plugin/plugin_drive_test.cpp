// What PluginDrive::load refuses, each with one clear message: a file that is missing or not a
// regular file, one that is not a shared object, a plugin without the entry object, one built
// for another ABI version or with a table of another size, a null function, and a create that
// fails (its text bounded and reduced to printable ASCII). A refused plugin is never called.
#include "server/drive/plugin/plugin_drive.hpp"

#include <dlfcn.h>
#include <gtest/gtest.h>
#include <netmc/drive_plugin.h>

#include <stdexcept>
#include <string>

namespace netmc::drive {
namespace {

// The message load() refuses `text` with ("" if it loads).
std::string refusal(const std::string& text) {
  try {
    PluginDrive::load(text);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

// A fake plugin's count of calls into it, read through a handle of the test's own (which also
// keeps the library, and so the count, loaded across load()'s dlopen and dlclose).
class CallCount {
 public:
  explicit CallCount(const char* path) : library_(::dlopen(path, RTLD_NOW | RTLD_LOCAL)) {
    if (library_ == nullptr) throw std::runtime_error(::dlerror());
    count_ = static_cast<int*>(::dlsym(library_, "fake_drive_plugin_calls"));
    if (count_ == nullptr) throw std::runtime_error("no fake_drive_plugin_calls");
  }
  ~CallCount() { ::dlclose(library_); }
  CallCount(const CallCount&) = delete;
  CallCount& operator=(const CallCount&) = delete;
  int calls() const { return *count_; }

 private:
  void* library_;
  int* count_ = nullptr;
};

TEST(PluginDriveLoad, RefusesAMissingFileNamingThePath) {
  EXPECT_EQ(refusal("/nonexistent/netmc/libdrive.so:ifname=eth0"),
            "plugin /nonexistent/netmc/libdrive.so: cannot read it: No such file or directory");
}

TEST(PluginDriveLoad, RefusesADirectory) { EXPECT_EQ(refusal("/tmp"), "plugin /tmp: not a regular file"); }

TEST(PluginDriveLoad, RefusesAFileThatIsNotASharedObjectWithTheLoadersReason) {
  const std::string message = refusal(NETMC_TEST_NOT_A_PLUGIN);
  EXPECT_EQ(
      message.rfind(std::string("plugin ") + NETMC_TEST_NOT_A_PLUGIN + ": cannot load it as a shared object: ", 0), 0u)
      << message;
  EXPECT_NE(message.find("invalid ELF header"), std::string::npos) << message;
}

TEST(PluginDriveLoad, RefusesAPluginWithoutTheEntryObject) {
  EXPECT_EQ(refusal(NETMC_TEST_PLUGIN_NO_ENTRY),
            std::string("plugin ") + NETMC_TEST_PLUGIN_NO_ENTRY +
                ": exports no netmc_drive_plugin (the entry object <netmc/drive_plugin.h> declares)");
}

TEST(PluginDriveLoad, RefusesAnotherAbiVersionNamingBothBeforeCallingIt) {
  CallCount count(NETMC_TEST_PLUGIN_ABI2);
  EXPECT_EQ(refusal(NETMC_TEST_PLUGIN_ABI2), std::string("plugin ") + NETMC_TEST_PLUGIN_ABI2 +
                                                 " was built for drive plugin ABI 2; this netmc-axis speaks ABI 1");
  EXPECT_EQ(count.calls(), 0);
}

TEST(PluginDriveLoad, RefusesATableOfAnotherSizeBeforeCallingIt) {
  CallCount count(NETMC_TEST_PLUGIN_TABLE_SIZE);
  const std::size_t size = sizeof(netmc_drive_plugin_table);
  EXPECT_EQ(refusal(NETMC_TEST_PLUGIN_TABLE_SIZE),
            std::string("plugin ") + NETMC_TEST_PLUGIN_TABLE_SIZE + ": its function table has " +
                std::to_string(size - sizeof(void*)) + " bytes; drive plugin ABI 1 has " + std::to_string(size) +
                " (built with another <netmc/drive_plugin.h>?)");
  EXPECT_EQ(count.calls(), 0);
}

TEST(PluginDriveLoad, RefusesANullFunctionNamingIt) {
  CallCount count(NETMC_TEST_PLUGIN_NULL_FUNCTION);
  EXPECT_EQ(refusal(NETMC_TEST_PLUGIN_NULL_FUNCTION), std::string("plugin ") + NETMC_TEST_PLUGIN_NULL_FUNCTION +
                                                          ": its function table has no cycle (a null pointer)");
  EXPECT_EQ(count.calls(), 0);
}

TEST(PluginDriveLoad, RefusesWhatCreateRefusesWithItsTextBoundedAndPrintable) {
  const std::string message = refusal(std::string(NETMC_TEST_PLUGIN_CREATE_FAILS) + ":speed=fast");
  const std::string prefix = std::string("plugin ") + NETMC_TEST_PLUGIN_CREATE_FAILS + ": refused its configuration: ";
  ASSERT_EQ(message.rfind(prefix, 0), 0u) << message;
  const std::string text = message.substr(prefix.size());
  // The escape, the newline and both bytes of the UTF-8 character as '?'; the rest of the buffer
  // (no NUL in it) read up to its end and no further.
  EXPECT_EQ(text.rfind("bad?[31m config???xxx", 0), 0u) << text;
  EXPECT_EQ(text.size(), std::size_t{NETMC_DRIVE_PLUGIN_ERROR_SIZE});
  for (const char c : message) EXPECT_TRUE(c >= 0x20 && c <= 0x7E) << message;
}

TEST(PluginDriveLoad, PassesTheSpecsRefusalOn) {
  EXPECT_EQ(refusal(std::string(NETMC_TEST_PLUGIN_EXAMPLE) + ":a2"),
            "--drive plugin: 'a2' has no '=' (settings are key=value)");
}

}  // namespace
}  // namespace netmc::drive
