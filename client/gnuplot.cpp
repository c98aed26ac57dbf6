#include "client/gnuplot.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <spdlog/spdlog.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "client/exclusive_file.hpp"

extern char** environ;

namespace netmc::cli {
namespace {

std::string read_tail(const std::filesystem::path& path, std::size_t max_chars) {
  std::ifstream file(path);
  std::ostringstream content;
  content << file.rdbuf();
  std::string text = content.str();
  if (text.size() > max_chars) text = "..." + text.substr(text.size() - max_chars);
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}

// Runs `program script` with stdout and stderr into `log`; returns the exit status.
int run_with_timeout(const std::string& program, const std::string& script,
                     const std::filesystem::path& log, std::chrono::milliseconds timeout) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  std::vector<std::string> arguments{program, script};
  std::vector<char*> argv;
  for (auto& argument : arguments) argv.push_back(argument.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) throw std::runtime_error("gnuplot: cannot start '" + program + "'");
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  int status = 0;
  while (true) {
    const pid_t done = waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (done < 0) throw std::runtime_error("gnuplot: lost track of the subprocess");
    if (std::chrono::steady_clock::now() > deadline) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      throw std::runtime_error("gnuplot: no result within " + std::to_string(timeout.count()) +
                               " ms (script " + script + ")");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

std::optional<std::string> find_gnuplot() {
  if (const char* configured = std::getenv("NETMC_GNUPLOT"); configured && *configured) {
    if (access(configured, X_OK) == 0) return std::string(configured);
    return std::nullopt;
  }
  const char* path = std::getenv("PATH");
  std::stringstream directories(path ? path : "/usr/bin:/bin");
  for (std::string directory; std::getline(directories, directory, ':');) {
    if (directory.empty()) continue;
    const auto candidate = std::filesystem::path(directory) / "gnuplot";
    if (access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return std::nullopt;
}

std::string gnuplot_quote(const std::string& text) {
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    // gnuplot's own escape of a quote ('') fails where two come together: none are let in.
    if (byte < 0x20 || byte == 0x7f || c == '\'') {
      throw std::invalid_argument("path for gnuplot: expected no control characters (line breaks, tabs) and no ' in '" +
                                  gnuplot_text(text) + "'");
    }
  }
  return "'" + text + "'";
}

std::string gnuplot_text(const std::string& text) {
  std::string out;
  out.reserve(text.size() + 8);
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) {
      out += ' ';
    } else if (c == '\'' || c == '`') {
      out += "\xE2\x80\x99";  // shown as a typographic apostrophe: no quote reaches the script
    } else if (c == '_' || c == '^' || c == '@' || c == '&' || c == '{' || c == '}' || c == '~' || c == '\\') {
      out += '\\';  // one backslash: enhanced-text escape inside single quotes
      out += c;
    } else {
      out += c;
    }
  }
  return out;
}

void require_gnuplot() {
  if (!find_gnuplot()) {
    throw std::runtime_error("plot: gnuplot not found (install the Debian package gnuplot-nox, "
                             "or set NETMC_GNUPLOT to its path)");
  }
}

std::vector<std::string> render_figures(const std::vector<Figure>& figures,
                                        const std::string& out_dir, FigureFormats formats,
                                        const std::string& set_name, std::chrono::milliseconds timeout) {
  require_gnuplot();
  const auto gnuplot = find_gnuplot();
  const std::filesystem::path out = std::filesystem::absolute(out_dir);
  const std::filesystem::path data = out / "data";
  std::error_code error;
  std::filesystem::create_directories(data, error);
  if (error) throw std::runtime_error(out_dir + ": cannot create the figure directory");

  // Two scripts with the same figures: the kept one (data/SET.gp) writes the final names
  // relative to the figure directory, to edit and redraw in place; the one run now starts with a
  // cd there and writes fresh temporary files, renamed over the targets once gnuplot succeeded.
  const std::string set = set_name.empty() ? "figures" : set_name;
  std::string kept = "# netmc figures (" + set + "): edit, then redraw them in place with\n#   cd " + out.string() +
                     " && gnuplot data/" + set + ".gp\n";
  std::string run = "cd " + gnuplot_quote(out.string()) + "\n";
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> outputs;  // partial -> final
  for (const auto& figure : figures) {
    for (const bool svg : {false, true}) {
      if (svg ? !formats.svg : !formats.png) continue;
      const std::string name = figure.name + (svg ? ".svg" : ".png");
      const auto target = out / name;
      const auto partial = create_exclusive_temporary(target);  // gnuplot writes here
      outputs.emplace_back(partial, target);
      std::string terminal = "reset session\n";
      terminal += svg ? "set terminal svg size " + std::to_string(figure.width_px) + "," +
                            std::to_string(figure.height_px) +
                            " dynamic enhanced font 'Sans,12' background rgb 'white'\n"
                      : "set terminal pngcairo size " + std::to_string(figure.width_px) + "," +
                            std::to_string(figure.height_px) + " enhanced font 'Sans,11'\n";
      const std::string body = figure.body + "\nunset multiplot\nset output\n\n";
      kept += terminal + "set output " + gnuplot_quote(name) + "\n" + body;
      run += terminal + "set output " + gnuplot_quote(partial.string()) + "\n" + body;
    }
  }
  const auto kept_path = data / (set + ".gp");
  write_file_atomically(kept_path.string(), kept);
  const auto script_path = create_exclusive_temporary(kept_path);
  write_file_atomically(script_path.string(), run);
  struct RemoveScript {
    std::filesystem::path path;
    ~RemoveScript() {
      std::error_code ignored;
      std::filesystem::remove(path, ignored);
    }
  } remove_script{script_path};
  const auto log = data / "gnuplot.log";
  const int status = run_with_timeout(*gnuplot, script_path.string(), log, timeout);
  if (status != 0) {
    for (const auto& [partial, target] : outputs) std::filesystem::remove(partial, error);
    throw std::runtime_error("gnuplot failed (exit " + std::to_string(status) + ") on " +
                             kept_path.string() + ": " + read_tail(log, 600));
  }
  if (const std::string notes = read_tail(log, 2000); !notes.empty()) {
    spdlog::info("gnuplot said: {}", notes);
  }
  spdlog::info("plot: {} figures drawn by {} ({})", figures.size(), *gnuplot, kept_path.string());
  std::vector<std::string> written;
  for (const auto& [partial, target] : outputs) {
    if (!std::filesystem::exists(partial) || std::filesystem::file_size(partial) == 0) {
      throw std::runtime_error("gnuplot wrote nothing to " + target.string() + ": " + read_tail(log, 600));
    }
    std::filesystem::rename(partial, target, error);
    if (error) throw std::runtime_error(target.string() + ": cannot rename into place");
    written.push_back(target.string());
  }
  return written;
}

}  // namespace netmc::cli
