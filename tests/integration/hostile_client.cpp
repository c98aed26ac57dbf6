// Test tool: a hostile (or careless) client of netmc-server's management endpoint. Each case is
// an attack that once hurt the server; it prints "PASS case: what happened" when the server
// defends itself and "FAIL case: ..." otherwise, and exits 1 if any case failed.
// Needs a server whose axis nodes host x and y (plant seed001, lockstep), started with
// --max-connections MAX, and $NETMC_TOKEN_FILE naming its token file if it asks for one. Case
// unread reads the server's memory from /proc (--server-pid); case silent connects from
// 127.0.0.2-40 too, so the server must listen on 127.0.0.1.

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <array>
#include <chrono>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "server/management/access_token.hpp"
#include "server/management/frame_codec.hpp"
#include "server/management/management_client.hpp"

namespace {

using namespace std::chrono_literals;
using netmc::management::ManagementClient;

std::string g_server;
int g_failures = 0;

void verdict(bool passed, const std::string& name, const std::string& detail) {
  fmt::print("{} {}: {}\n", passed ? "PASS" : "FAIL", name, detail);
  std::fflush(stdout);
  if (!passed) ++g_failures;
}

netmc::v1::JobSpec small_job() {
  netmc::v1::JobSpec spec;
  auto& circle = *spec.mutable_trajectory()->mutable_circle();
  circle.set_radius_m(0.01);
  circle.set_center_x_m(0.05);
  circle.set_center_y_m(0.05);
  circle.set_period_s(8.0);
  spec.mutable_controller()->set_name("adrc");
  return spec;
}

// Submits and returns the first answer (nullopt: none within 5 s).
std::optional<netmc::v1::Response> submit(ManagementClient& client, const netmc::v1::JobSpec& spec,
                                          std::uint64_t id = 1) {
  netmc::v1::Request request;
  request.set_request_id(id);
  *request.mutable_submit()->mutable_spec() = spec;
  client.send(request);
  return client.receive(5s);
}

std::string error_of(const std::optional<netmc::v1::Response>& response) {
  if (!response) return "(no answer)";
  return response->has_error() ? response->error().message() : "(not an error: " + response->ShortDebugString().substr(0, 80) + ")";
}

void refused(const std::string& name, const netmc::v1::JobSpec& spec, const std::string& expected) {
  ManagementClient client(g_server, 5s);
  const auto started = std::chrono::steady_clock::now();
  const auto answer = submit(client, spec);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
  const std::string message = error_of(answer);
  verdict(answer && answer->has_error() && message.find(expected) != std::string::npos && ms < 2000.0, name,
          fmt::format("refused in {:.0f} ms: {}", ms, message));
}

void server_files() {
  for (const char* path : {"/etc/shadow", "/dev/zero"}) {
    auto spec = small_job();
    spec.mutable_downlink()->mutable_delay()->mutable_trace()->set_path(path);
    refused(std::string("trace path ") + path, spec, "names no file");
  }
}

void absurd_values() {
  auto spec = small_job();
  spec.set_sample_period_s(1e308);
  refused("sample period 1e308 s", spec, "sample_period");
  spec = small_job();
  spec.set_iterations(1000000000);
  refused("1e9 iterations", spec, "iterations");
  spec = small_job();
  spec.mutable_downlink()->mutable_delay()->set_constant_s(1e308);
  refused("delay 1e308 s", spec, "downlink.delay");
  spec = small_job();
  spec.mutable_sensor()->set_noise_stddev_m(std::numeric_limits<double>::quiet_NaN());
  refused("sensor noise NaN", spec, "sensor.noise_stddev");
  spec = small_job();
  auto& lissajous = *spec.mutable_trajectory()->mutable_lissajous();
  lissajous.set_amplitude_x_m(0.01);
  lissajous.set_amplitude_y_m(0.01);
  lissajous.set_frequency_x(4000000000u);
  lissajous.set_frequency_y(4000000001u);
  lissajous.set_period_s(8.0);
  refused("lissajous p, q ~ 4e9", spec, "frequency");
  spec = small_job();
  spec.set_name(std::string(15 << 20, 'n'));
  refused("15 MB job name", spec, "name");
  spec = small_job();
  auto& spline = *spec.mutable_trajectory()->mutable_spline();
  for (int i = 0; i < 8000; ++i) {
    auto& point = *spline.add_points();
    point.set_x_m(0.05 * std::cos(i * 1e-3));
    point.set_y_m(0.05 * std::sin(i * 1e-3));
  }
  spline.mutable_feed()->set_feed_m_s(0.01);
  spline.mutable_feed()->set_max_normal_acceleration_m_s2(1.0);
  refused("8000-point spline", spec, "points");
}

// A long job (20 iterations of 8 s, a few seconds in lockstep) on another connection.
netmc::v1::JobSpec long_job() {
  auto spec = small_job();
  spec.set_iterations(200);
  spec.set_name("long job");
  return spec;
}

void cancel_by_another_connection() {
  ManagementClient owner(g_server, 5s);
  const auto accepted = submit(owner, long_job());
  if (!accepted || !accepted->has_accepted()) {
    verdict(false, "cancel from another connection", "the job was not accepted: " + error_of(accepted));
    return;
  }
  ManagementClient intruder(g_server, 5s);
  netmc::v1::Request cancel;
  cancel.set_request_id(9);
  cancel.mutable_cancel()->set_job_id(accepted->accepted().job_id());
  intruder.send(cancel);
  const auto answer = intruder.receive(5s);
  verdict(answer && answer->has_error() && error_of(answer).find("another connection") != std::string::npos,
          "cancel from another connection", error_of(answer));
  // Job tokens it guessed: one of the right form, one of a MiB; both refused, neither cancels.
  cancel.set_request_id(11);
  cancel.mutable_cancel()->set_cancel_token(std::string(64, '0'));
  intruder.send(cancel);
  const auto guessed = intruder.receive(5s);
  verdict(guessed && guessed->has_error() && error_of(guessed).find("not its token") != std::string::npos,
          "cancel with a guessed job token", error_of(guessed));
  cancel.set_request_id(12);
  cancel.mutable_cancel()->set_cancel_token(std::string(1 << 20, 'x'));
  intruder.send(cancel);
  const auto oversized = intruder.receive(5s);
  verdict(oversized && oversized->has_error() && error_of(oversized).find("longer than") != std::string::npos,
          "cancel with a 1 MiB job token", error_of(oversized));
  // The owner may, and its job ends cancelled.
  cancel.mutable_cancel()->clear_cancel_token();
  cancel.set_request_id(10);
  owner.send(cancel);
  std::string state;
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  while (state.empty() && std::chrono::steady_clock::now() < deadline) {
    const auto response = owner.receive(1s);
    if (response && response->has_finished()) state = response->finished().state();
  }
  verdict(state == "cancelled", "cancel by its own connection", "job ended " + (state.empty() ? "(not seen)" : state));
}

void disconnect_cancels() {
  std::uint64_t job_id = 0;
  {
    ManagementClient owner(g_server, 5s);
    const auto accepted = submit(owner, long_job());
    if (accepted && accepted->has_accepted()) job_id = accepted->accepted().job_id();
  }  // the client goes away
  // The server's log says what happened to it (checked by the script); here: its status.
  ManagementClient observer(g_server, 5s);
  std::string state;
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  while (state != "cancelled" && std::chrono::steady_clock::now() < deadline) {
    netmc::v1::Request status;
    status.set_request_id(11);
    status.mutable_status()->set_job_id(job_id);
    observer.send(status);
    const auto answer = observer.receive(2s);
    if (answer && answer->has_status() && answer->status().jobs_size() == 1) state = answer->status().jobs(0).state();
    std::this_thread::sleep_for(100ms);
  }
  verdict(job_id != 0 && state == "cancelled", "client disconnects mid-job", fmt::format("job {} {}", job_id, state));
}

// One connection asks to watch a job again and again: the server follows it for a bounded
// number of watchers (16), refuses the rest, and ends every watch it took when the job ends.
void many_watches() {
  ManagementClient owner(g_server, 5s);
  const auto accepted = submit(owner, long_job());
  if (!accepted || !accepted->has_accepted()) {
    verdict(false, "watch flood", "the job was not accepted: " + error_of(accepted));
    return;
  }
  const std::uint64_t job_id = accepted->accepted().job_id();
  ManagementClient watcher(g_server, 5s);
  constexpr int kWatches = 40;
  for (int i = 0; i < kWatches; ++i) {
    netmc::v1::Request watch;
    watch.set_request_id(100 + static_cast<std::uint64_t>(i));
    watch.mutable_watch()->set_job_id(job_id);
    watcher.send(watch);
  }
  netmc::v1::Request unknown;
  unknown.set_request_id(99);
  unknown.mutable_watch()->set_job_id(std::numeric_limits<std::uint64_t>::max());
  watcher.send(unknown);
  // Once every watch is answered (the server reads requests only as fast as their answers are
  // taken), the owner cancels; every watch that was taken then ends, cancelled.
  netmc::v1::Request cancel;
  cancel.set_request_id(2);
  cancel.mutable_cancel()->set_job_id(job_id);
  bool cancelled = false;
  int taken = 0, refused = 0, ended = 0;
  std::string refusal, unknown_answer;
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  while ((taken == 0 || ended < taken || unknown_answer.empty()) && std::chrono::steady_clock::now() < deadline) {
    if (!cancelled && taken + refused == kWatches && !unknown_answer.empty()) {
      owner.send(cancel);
      cancelled = true;
    }
    const auto response = watcher.receive(1s);
    if (!response) continue;
    if (response->request_id() == 99) {
      unknown_answer = error_of(response);
    } else if (response->has_status()) {
      ++taken;
    } else if (response->has_error()) {
      ++refused;
      refusal = response->error().message();
    } else if (response->has_finished() && response->finished().state() == "cancelled") {
      ++ended;
    }
  }
  verdict(taken == 16 && refused == kWatches - 16 && ended == taken && refusal.find("watchers already") != std::string::npos,
          "watch flood", fmt::format("{} watches of job {} on one connection: {} taken, {} refused ({}), {} ended with the job",
                                     kWatches, job_id, taken, refused, refusal, ended));
  verdict(unknown_answer.find("watch: no job") != std::string::npos, "watch of job 2^64-1", unknown_answer);
}

void connection_cap(int max_connections) {
  std::vector<std::unique_ptr<ManagementClient>> held;
  for (int i = 0; i < max_connections; ++i) held.push_back(std::make_unique<ManagementClient>(g_server, 5s));
  for (auto& client : held) {  // each session is set up before the next one is counted
    netmc::v1::Request status;
    status.set_request_id(12);
    status.mutable_status();
    client->send(status);
    client->receive(5s);
  }
  ManagementClient extra(g_server, 5s);
  netmc::v1::Request status;
  status.set_request_id(13);
  status.mutable_status();
  std::string message;
  try {
    extra.send(status);
    message = error_of(extra.receive(5s));
  } catch (const std::exception& error) {
    message = error.what();
  }
  verdict(message.find("server busy") != std::string::npos, "one connection over the cap", message);
  held.clear();
}

void without_token() {
  // A raw connection: ManagementClient would add the token of $NETMC_TOKEN_FILE.
  boost::asio::io_context io;
  boost::asio::ip::tcp::socket socket(io);
  const auto colon = g_server.rfind(':');
  socket.connect({boost::asio::ip::make_address(g_server.substr(0, colon)),
                  static_cast<std::uint16_t>(std::stoi(g_server.substr(colon + 1)))});
  netmc::v1::Request status;
  status.set_request_id(14);
  status.mutable_status();
  boost::asio::write(socket, boost::asio::buffer(netmc::management::encode_frame(status)));
  std::string received;
  boost::system::error_code error;
  std::array<char, 512> buffer{};
  while (!error) received.append(buffer.data(), socket.read_some(boost::asio::buffer(buffer), error));
  netmc::management::FrameDecoder decoder;
  decoder.feed(received.data(), received.size());
  netmc::v1::Response response;
  const auto payload = decoder.next();
  const bool parsed = payload && response.ParseFromString(*payload);
  verdict(parsed && response.has_error() && response.error().message().find("unauthenticated") != std::string::npos &&
              error == boost::asio::error::eof,
          "request without the token", parsed ? error_of(response) + ", then closed" : "no answer");
}

// The server's resident memory in MiB (VmRSS of /proc/PID/status); 0 when unknown.
double server_rss_mib(int pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmRSS:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  }
  return 0.0;
}

std::pair<std::string, std::uint16_t> server_address() {
  const auto colon = g_server.rfind(':');
  return {g_server.substr(0, colon), static_cast<std::uint16_t>(std::stoi(g_server.substr(colon + 1)))};
}

// A status request with the token of $NETMC_TOKEN_FILE (a raw socket adds none by itself).
netmc::v1::Request status_with_token(std::uint64_t id) {
  netmc::v1::Request status;
  status.set_request_id(id);
  status.mutable_status();
  if (const auto token = netmc::management::client_token_from_environment()) status.set_token(token->value());
  return status;
}

// Asks another connection for the status; how long the answer took, or why there was none.
std::string other_client_answered() {
  const auto started = std::chrono::steady_clock::now();
  ManagementClient other(g_server, 5s);
  other.send(status_with_token(2));
  const auto answer = other.receive(5s);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
  if (!answer || answer->request_id() != 2 || answer->has_error()) return "";  // no job yet: an empty answer
  return fmt::format("{:.0f} ms", ms);
}

// Issue 26: 623 k status requests from a client that never reads took the server to 2.9 GB.
// A status table as a busy lab's: 16 jobs with names of the longest kind, each cancelled.
void fill_status_table() {
  ManagementClient owner(g_server, 5s);
  for (int i = 0; i < 16; ++i) {
    auto spec = long_job();
    spec.set_name(fmt::format("{:0>256}", i));
    const auto accepted = submit(owner, spec, 200 + static_cast<std::uint64_t>(i));
    if (!accepted || !accepted->has_accepted()) continue;
    netmc::v1::Request cancel;
    cancel.set_request_id(300);
    cancel.mutable_cancel()->set_job_id(accepted->accepted().job_id());
    owner.send(cancel);
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    for (auto response = owner.receive(1s); std::chrono::steady_clock::now() < deadline; response = owner.receive(1s)) {
      if (response && response->has_finished()) break;
    }
  }
}

void unread_answers(int server_pid, double bound_mib) {
  fill_status_table();
  constexpr int kRequests = 623000;
  std::string flood;
  for (int i = 0; i < kRequests; ++i) flood += netmc::management::encode_frame(status_with_token(100));
  const auto [host, port] = server_address();
  boost::asio::io_context io;
  boost::asio::ip::tcp::socket socket(io);
  socket.connect({boost::asio::ip::make_address(host), port});
  socket.non_blocking(true);
  const double rss_before = server_rss_mib(server_pid);
  double rss_most = rss_before;
  std::size_t written = 0;
  const auto started = std::chrono::steady_clock::now();
  // Writes as long as the server takes them, for 20 s at most; then 3 s more for it to work.
  auto quiet_since = started;
  while (std::chrono::steady_clock::now() - started < 20s && std::chrono::steady_clock::now() - quiet_since < 3s) {
    boost::system::error_code error;
    const std::size_t n = written < flood.size()
                              ? socket.write_some(boost::asio::buffer(flood.data() + written, flood.size() - written), error)
                              : 0;
    if (error && error != boost::asio::error::would_block) break;
    written += n;
    if (n > 0) quiet_since = std::chrono::steady_clock::now();
    rss_most = std::max(rss_most, server_rss_mib(server_pid));
    if (rss_most > bound_mib) break;  // the verdict is known; spare the machine the rest
    if (n == 0) std::this_thread::sleep_for(50ms);
  }
  const std::string answered = other_client_answered();
  const double requests_written = static_cast<double>(written) / static_cast<double>(flood.size()) * kRequests;
  verdict(rss_most > 0.0 && rss_most < bound_mib && !answered.empty(), "requests never read",
          fmt::format("{:.0f} of {} status requests taken by the server, never read back: its VmRSS {:.0f} MiB "
                      "before, {:.0f} MiB at most (bound {:.0f}); another client {}",
                      requests_written, kRequests, rss_before, rss_most, bound_mib,
                      answered.empty() ? "not answered" : "answered in " + answered));
}

// Issue 26: 32 silent connections filled the cap; "server busy" for everyone, the token's holder
// included, for the 600 s idle timeout. From one address, then from 39 others (any 127.x reaches
// a server on 127.0.0.1).
void silent_connections(int authentication_timeout_s) {
  const auto [host, port] = server_address();
  boost::asio::io_context io;
  std::vector<std::unique_ptr<boost::asio::ip::tcp::socket>> silent;
  const auto open_from = [&, port = port, host = host](const std::string& source) {
    auto socket = std::make_unique<boost::asio::ip::tcp::socket>(io);
    socket->open(boost::asio::ip::tcp::v4());
    socket->bind({boost::asio::ip::make_address(source), 0});
    socket->connect({boost::asio::ip::make_address(host), port});
    socket->non_blocking(true);
    silent.push_back(std::move(socket));
  };
  const auto opened = std::chrono::steady_clock::now();
  for (int i = 0; i < 40; ++i) open_from("127.0.0.1");
  for (int source = 2; source <= 40; ++source) open_from("127.0.0." + std::to_string(source));
  std::this_thread::sleep_for(300ms);
  const std::string answered = other_client_answered();
  verdict(!answered.empty(), "79 silent connections, then the token's holder",
          answered.empty() ? "not answered" : "answered in " + answered);
  const auto still_open = [](boost::asio::ip::tcp::socket& socket) {
    std::array<char, 256> buffer{};
    boost::system::error_code error;
    while (!error) socket.read_some(boost::asio::buffer(buffer), error);
    return error == boost::asio::error::would_block;
  };
  std::size_t open = silent.size();
  while (open > 0 && std::chrono::steady_clock::now() - opened < std::chrono::seconds(authentication_timeout_s + 5)) {
    std::this_thread::sleep_for(100ms);
    open = static_cast<std::size_t>(std::count_if(silent.begin(), silent.end(), [&](auto& s) { return still_open(*s); }));
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - opened).count();
  verdict(open == 0, "silent connections closed",
          fmt::format("{} of {} still open {:.1f} s after they connected (the server's authentication timeout: {} s)",
                      open, silent.size(), s, authentication_timeout_s));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"netmc_hostile_client: attacks a netmc-server's management endpoint, case by case"};
  std::vector<std::string> cases;
  int max_connections = 8;
  int server_pid = 0;
  double rss_bound_mib = 200.0;
  int authentication_timeout_s = 5;
  app.add_option("--server", g_server, "HOST:PORT")->required();
  app.add_option("--max-connections", max_connections, "The server's --max-connections");
  app.add_option("--server-pid", server_pid, "netmc-server's process id, for its memory (case unread)");
  app.add_option("--rss-bound", rss_bound_mib, "MiB the server's VmRSS must stay under (case unread)");
  app.add_option("--authentication-timeout", authentication_timeout_s, "The server's --authentication-timeout");
  app.add_option("cases", cases,
                 "files, values, cancel, disconnect, watch, connections, token, unread, silent (default: all but "
                 "token, unread, silent)");
  CLI11_PARSE(app, argc, argv);
  if (cases.empty()) cases = {"files", "values", "cancel", "disconnect", "watch", "connections"};
  const std::map<std::string, std::function<void()>> all{
      {"files", server_files},
      {"values", absurd_values},
      {"cancel", cancel_by_another_connection},
      {"disconnect", disconnect_cancels},
      {"watch", many_watches},
      {"connections", [&] { connection_cap(max_connections); }},
      {"token", without_token},
      {"unread", [&] { unread_answers(server_pid, rss_bound_mib); }},
      {"silent", [&] { silent_connections(authentication_timeout_s); }}};
  for (const auto& name : cases) {
    const auto it = all.find(name);
    if (it == all.end()) {
      fmt::print(stderr, "unknown case {}\n", name);
      return 2;
    }
    try {
      it->second();
    } catch (const std::exception& error) {
      verdict(false, name, std::string("the client saw: ") + error.what());
    }
  }
  return g_failures == 0 ? 0 : 1;
}
