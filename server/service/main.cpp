// netmc-server: the central controller. Discovers axis nodes over DDS, runs submitted jobs on
// them (lockstep with the same job runner as `netmc sim`, or realtime on the wall clock) and
// serves the management endpoint (Boost.Asio TCP or TLS, length-prefixed protobuf: run, submit,
// watch, status, jobs, cancel, nodes, reset) and the lab console. See docs/architecture.md.

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>
#include <utility>  // before Asio: Boost 1.74's awaitable.hpp uses std::exchange unincluded

#include <boost/asio.hpp>

#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "server/job/presets/presets.hpp"
#include "server/console/console_service.hpp"
#include "server/console/http_console.hpp"
#include "server/dds/dds_options_cli.hpp"
#include "server/log/process_log.hpp"
#include "server/management/access_token.hpp"
#include "server/management/host_port.hpp"
#include "server/management/management_server.hpp"
#include "server/management/tls_settings.hpp"
#include "server/plugins/loaded_component_plugin.hpp"
#include "server/realtime/realtime_options_cli.hpp"
#include "server/service/job_service.hpp"
#include "server/service/node_directory.hpp"

int main(int argc, char** argv) {
  CLI::App app{"netmc-server: closes contouring loops of remote axis nodes over DDS"};
  app.set_version_flag("--version", std::string("netmc-server ") + NETMC_VERSION);
  // Not 7400: that is DDS domain 0's discovery port.
  std::string listen = "127.0.0.1:7300";
  int axis_timeout_ms = 2000;
  int discovery_timeout_ms = 10000;
  int silence_ms = 500;
  netmc::dds::TimeBase time_base = netmc::dds::TimeBase::monotonic;
  netmc::dds::DdsOptions dds;
  dds.name = "netmc-server";
  app.add_option("--listen", listen, "Management endpoint HOST:PORT (port 0: any free port)")->envname("NETMC_LISTEN");
  app.add_option("--dds-name", dds.name,
                 "The server's DDS participant name, and its certificate's name under --security (default netmc-server)");
  app.add_option("--axis-timeout", axis_timeout_ms,
                 "Milliseconds an axis may take to answer before the job fails")
      ->check(CLI::Range(1, 600000));
  app.add_option("--discovery-timeout", discovery_timeout_ms,
                 "Milliseconds to wait for the axis nodes of a job")
      ->check(CLI::Range(1, 600000));
  app.add_option("--axis-silence", silence_ms,
                 "Realtime: milliseconds without any feedback from an axis before the job fails "
                 "(lost samples alone do not fail a job)")
      ->check(CLI::Range(1, 600000));
  int positioning_timeout_ms = 60000;
  app.add_option("--positioning-timeout", positioning_timeout_ms,
                 "Realtime: milliseconds for every axis to stand ready at an iteration's start (hardware drives "
                 "are moved there between iterations)")
      ->check(CLI::Range(1, 3600000));
  int max_running_jobs = 32;
  app.add_option("--max-running-jobs", max_running_jobs,
                 "Jobs run at once, each on disjoint axes and its own thread; more wait in the queue")
      ->check(CLI::Range(1, 256));
  int max_queued_jobs = 256;
  app.add_option("--max-queued-jobs", max_queued_jobs,
                 "Jobs waiting (for validation or for their axes); a submit beyond is refused")
      ->check(CLI::Range(1, 100000));
  std::string state_dir;
  app.add_option("--state-dir", state_dir,
                 "Keep every accepted job, its iterations and its result in DIR/jobs.sqlite: after a crash or "
                 "restart the queue runs on, a job that was running is failed with what it finished, and netmc "
                 "status, watch and jobs answer as before (docs/operations/job-store.md); default: memory only")
      ->envname("NETMC_STATE_DIR");
  int keep_jobs = 10000;
  app.add_option("--keep-jobs", keep_jobs, "With --state-dir: ended jobs kept, the newest; older ones are deleted")
      ->check(CLI::Range(1, 10000000));
  std::string backup_file;
  app.add_option("--backup", backup_file,
                 "With --state-dir: write a consistent copy of the job store to FILE (one file, what the "
                 "write-ahead log holds included; beside a running server) and exit")
      ->type_name("FILE");
  double keep_days = 90.0;
  app.add_option("--keep-days", keep_days, "With --state-dir: ended jobs older than this are deleted")
      ->check(CLI::Range(0.001, 36500.0));
  int hold_wait_ms = 15000;
  app.add_option("--hold-wait", hold_wait_ms,
                 "Milliseconds a job waits for an axis another server holds (a restarted server's predecessor holds "
                 "its axes for the nodes' 10 s lease); 0: refuse at once")
      ->check(CLI::Range(0, 600000));
  netmc::management::ManagementLimits limits;
  int max_connections = static_cast<int>(limits.max_connections);
  app.add_option("--max-connections", max_connections,
                 "Open management connections; one more is refused with a message")
      ->check(CLI::Range(1, 4096));
  int idle_timeout_s = 600;
  app.add_option("--idle-timeout", idle_timeout_s,
                 "Seconds a management connection with no job of its own may stay silent before it is closed")
      ->check(CLI::Range(1, 86400));
  int authentication_timeout_s = static_cast<int>(
      std::chrono::duration_cast<std::chrono::seconds>(limits.session.authentication_timeout).count());
  app.add_option("--authentication-timeout", authentication_timeout_s,
                 "Seconds a new management connection has to show the token (without --token-file: to send a "
                 "request), TLS handshake included, before it is closed")
      ->check(CLI::Range(1, 3600));
  app.add_option("--max-unauthenticated", limits.max_unauthenticated,
                 "Management connections not yet authenticated; one more closes the oldest of them")
      ->check(CLI::Range(1, 4096));
  app.add_option("--max-unauthenticated-per-address", limits.max_unauthenticated_per_address,
                 "The same, from one remote address")
      ->check(CLI::Range(1, 4096));
  std::string token_file;
  app.add_option("--token-file", token_file,
                 "Clients must show the token in this file (one line, 16+ characters; clients name the "
                 "file in $NETMC_TOKEN_FILE); default: no token asked (keep --listen on loopback then)");
  std::string admin_token_file;
  std::string tls_cert, tls_key;
  app.add_option("--tls-cert", tls_cert,
                 "PEM certificate (chain) of the management endpoint: it then speaks TLS 1.3 only, and clients "
                 "set NETMC_TLS_CA to the CA file that signed it (scripts/make-lab-pki.sh --management HOST)")
      ->envname("NETMC_SERVER_TLS_CERT");
  app.add_option("--tls-key", tls_key, "PEM private key of --tls-cert")->envname("NETMC_SERVER_TLS_KEY");
  std::string tls_client_ca;
  app.add_option("--tls-client-ca", tls_client_ca,
                 "With --tls-cert: clients must show a certificate this CA signed (NETMC_TLS_CERT, NETMC_TLS_KEY), "
                 "besides the token")
      ->envname("NETMC_SERVER_TLS_CLIENT_CA");
  app.add_option("--admin-token-file", admin_token_file,
                 "A client showing the token in this file may also cancel jobs of other connections "
                 "(netmc cancel); it is accepted wherever --token-file's is")
      ->envname("NETMC_ADMIN_TOKEN_FILE");
  std::vector<std::string> allowed_plugins;
  app.add_option("--allow-plugin", allowed_plugins,
                 "A controller plugin (shared object) jobs may name as --controller plugin:PATH[:...], by this "
                 "exact path; loaded and checked at start. Repeatable; default: none (a job naming a plugin is "
                 "refused: a client cannot make the server load code)");
  std::string http_listen;
  app.add_option("--http", http_listen,
                 "Serve the lab console and /metrics on HOST:PORT (:PORT: 127.0.0.1; port 0: any free port), with "
                 "--tls-cert's certificate if given; read-only without --token-file's or --admin-token-file's token "
                 "(docs/operations/console.md); default: off")
      ->envname("NETMC_HTTP");
  std::vector<std::string> http_allow_hosts;
  app.add_option("--http-allow-host", http_allow_hosts,
                 "A name (or address) browsers reach the console by, besides localhost, 127.0.0.1, ::1 and --http's "
                 "address: requests whose Host or Origin names another are refused (403), so no other site's page "
                 "can use the console. Repeatable; '*' allows any (only behind a proxy that checks them)")
      ->check([](const std::string& host) -> std::string {
        if (host == "*" || netmc::console::RequestOriginPolicy::host_of(host)) return "";
        return "expected a host name or address (no scheme, no path), or '*'";
      });
  netmc::dds::add_time_base_option(app, time_base);
  netmc::dds::add_dds_options(app, dds);
  netmc::realtime::RealtimeScheduling scheduling;
  netmc::realtime::add_realtime_options(app, scheduling);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return e.get_exit_code() == 0 ? code : 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "netmc-server: error: " << e.what() << "\n";
    return 2;
  }
  if (!backup_file.empty()) {
    if (state_dir.empty()) {
      std::cerr << "netmc-server: error: --backup: needs --state-dir DIR (the store to copy)\n";
      return 2;
    }
    try {
      const std::size_t jobs = netmc::store::JobStore::backup(state_dir, backup_file);
      std::cout << "netmc-server: backed up " << jobs << " jobs of " << state_dir << "/jobs.sqlite to " << backup_file
                << "\n";
      return 0;
    } catch (const netmc::store::StoreError& error) {
      std::cerr << "netmc-server: error: " << error.what() << "\n";
      return 1;
    }
  }
  std::string listen_address;
  std::uint16_t port = 0;
  std::string http_address;  // empty: no console
  std::uint16_t http_port = 0;
  try {
    // A host name (localhost, the lab host's name) binds to the address it resolves to.
    const auto where = netmc::management::parse_host_port(listen, "--listen", true);
    port = static_cast<std::uint16_t>(std::stoi(where.port));
    boost::system::error_code error;
    boost::asio::io_context resolving;
    const auto found = boost::asio::ip::tcp::resolver(resolving).resolve(where.host, where.port, error);
    if (error || found.empty()) {
      throw std::invalid_argument("--listen: cannot resolve '" + where.host + "'" +
                                  (error ? ": " + error.message() : std::string()));
    }
    listen_address = found.begin()->endpoint().address().to_string();
    if (!http_listen.empty()) {
      if (http_listen.front() == ':') http_listen = "127.0.0.1" + http_listen;
      const auto http_where = netmc::management::parse_host_port(http_listen, "--http", true);
      const auto http_found = boost::asio::ip::tcp::resolver(resolving).resolve(http_where.host, http_where.port, error);
      if (error || http_found.empty()) {
        throw std::invalid_argument("--http: cannot resolve '" + http_where.host + "'" +
                                    (error ? ": " + error.message() : std::string()));
      }
      http_address = http_found.begin()->endpoint().address().to_string();
      http_port = static_cast<std::uint16_t>(std::stoi(http_where.port));
    }
  } catch (const std::invalid_argument& e) {
    std::cerr << "netmc-server: error: " << e.what() << "\n";
    return 2;
  }
  netmc::log::init("netmc-server");
  try {
    std::optional<netmc::management::AccessToken> token;
    if (!token_file.empty()) token = netmc::management::AccessToken::from_file(token_file);
    std::optional<netmc::management::AccessToken> admin_token;
    if (!admin_token_file.empty()) admin_token = netmc::management::AccessToken::from_file(admin_token_file);
    if (tls_cert.empty() != tls_key.empty()) {
      throw std::invalid_argument(tls_cert.empty() ? "--tls-key: needs --tls-cert" : "--tls-cert: needs --tls-key");
    }
    if (!tls_client_ca.empty() && tls_cert.empty()) throw std::invalid_argument("--tls-client-ca: needs --tls-cert");
    const auto tls =
        tls_cert.empty() ? nullptr : netmc::management::make_server_tls(tls_cert, tls_key, tls_client_ca);
    // Before the participant: its threads, and every job thread, inherit the scheduling.
    const auto scheduling_outcome = netmc::realtime::apply_process_scheduling(scheduling);
    for (const auto& fallback : scheduling_outcome.fallbacks) {
      spdlog::warn("{}; running without it", fallback);
    }
    netmc::dds::DdsContext context(dds);
    netmc::service::NodeDirectory nodes(context);
    netmc::service::ClockTracker clocks(context, nodes, time_base);
    netmc::service::JobServiceOptions options;
    options.axis_timeout = std::chrono::milliseconds(axis_timeout_ms);
    options.discovery_timeout = std::chrono::milliseconds(discovery_timeout_ms);
    options.silence_limit = std::chrono::milliseconds(silence_ms);
    options.time_base = time_base;
    options.max_running_jobs = static_cast<std::size_t>(max_running_jobs);
    options.max_queued_jobs = static_cast<std::size_t>(max_queued_jobs);
    options.positioning_timeout = std::chrono::milliseconds(positioning_timeout_ms);
    options.foreign_hold_wait = std::chrono::milliseconds(hold_wait_ms);
    options.admin_token_configured = !admin_token_file.empty();
    for (const auto& path : allowed_plugins) {
      try {
        const auto plugin = netmc::plugins::LoadedComponentPlugin::load(path);
        if (!plugin->provides_axis_controller()) throw std::invalid_argument("it provides no axis controller");
        spdlog::info("controller plugin {}: {}", path, plugin->description());
      } catch (const std::invalid_argument& error) {
        throw std::invalid_argument("--allow-plugin " + path.substr(0, 200) + ": " + error.what());
      }
    }
    options.allowed_plugins = allowed_plugins;
    // The console outlives the job service (declared first): a job thread that starts while the
    // service shuts down may still ask it for a live feed.
    std::unique_ptr<netmc::console::ConsoleService> console;
    if (!http_address.empty()) {
      options.live_cycles = [&console](std::uint64_t job_id) -> std::shared_ptr<netmc::sim::CycleListener> {
        return console ? console->live_cycles(job_id) : nullptr;
      };
    }
    if (!state_dir.empty()) {
      netmc::store::Retention retention;
      retention.keep_jobs = static_cast<std::size_t>(keep_jobs);
      retention.keep_for = std::chrono::seconds(static_cast<std::int64_t>(keep_days * 86400.0));
      try {
        options.store = std::make_shared<netmc::store::JobStore>(state_dir, retention);
      } catch (const netmc::store::StoreError& error) {
        throw std::invalid_argument(std::string("--state-dir: ") + error.what());
      }
    }
    netmc::service::JobService jobs(context, nodes, clocks, options);
    limits.max_connections = static_cast<std::size_t>(max_connections);
    limits.session.idle_timeout = std::chrono::seconds(idle_timeout_s);
    limits.session.authentication_timeout = std::chrono::seconds(authentication_timeout_s);
    boost::asio::io_context io;
    netmc::management::ManagementServer server(
        io, listen_address, port,
        {[&jobs, &token, &admin_token](netmc::management::Session& session, const netmc::v1::Request& request) {
          const bool admin = admin_token && admin_token->accepts(request.token());
          if (token && !admin && !token->accepts(request.token())) {
            netmc::v1::Response refusal;
            refusal.set_request_id(request.request_id());
            refusal.mutable_error()->set_message("unauthenticated: this server asks for its token "
                                                 "(set NETMC_TOKEN_FILE to the file that holds it)");
            session.send(refusal);
            session.close();
            return;
          }
          session.mark_authenticated();  // the token shown (or none asked): the pre-auth limits end
          jobs.handle(session.shared_from_this(), request, admin);
        }},
        limits, tls, [](const std::string& peer, const std::string& reason) {
          spdlog::warn("management connection from {} closed: TLS handshake failed: {}", peer, reason);
        });
    std::unique_ptr<netmc::console::HttpConsole> http;
    if (!http_address.empty()) {
      netmc::console::ConsoleOptions console_options;
      console_options.version = NETMC_VERSION;
      console_options.token_required = token.has_value() || admin_token.has_value();
      if (console_options.token_required) {
        console_options.authorize = [&token, &admin_token](const std::string& presented) -> std::optional<bool> {
          if (admin_token && admin_token->accepts(presented)) return true;
          if (token && token->accepts(presented)) return false;
          return std::nullopt;
        };
      }
      console_options.presets = netmc::presets::preset_names();
      console_options.preset_job = [](const std::string& name) { return netmc::presets::make_preset(name).jobs.front(); };
      console_options.management_connections = [&server] { return server.open_connections(); };
      console = std::make_unique<netmc::console::ConsoleService>(io, jobs, std::move(console_options));
      // A browser shows no client certificate: the console's TLS asks for none.
      const auto console_tls = tls_cert.empty() ? nullptr : netmc::management::make_server_tls(tls_cert, tls_key, "");
      auto origins = netmc::console::RequestOriginPolicy::loopback_and(http_address, http_allow_hosts);
      http = std::make_unique<netmc::console::HttpConsole>(io, *console, http_address, http_port, origins, console_tls);
      spdlog::info("console on {}://{}:{}/ ({}; answers to {})", console_tls ? "https" : "http", http_address,
                   http->port(),
                   token || admin_token ? "starting and cancelling jobs need the token"
                                        : "read-only: no --token-file, so no job is started or cancelled here",
                   origins.describe());
    }
    boost::asio::signal_set signals(io, SIGINT, SIGTERM);
    signals.async_wait([&](const boost::system::error_code&, int) {
      server.stop();
      if (http) http->stop();
      if (console) console->stop();
      io.stop();
    });
    spdlog::info("netmc {}, listening on {}:{} ({}), DDS domain {} ({}), server {}, time base {}, {}", NETMC_VERSION,
                 listen_address, server.port(),
                 tls ? netmc::management::describe_server_tls(*tls) : std::string("plain TCP, no TLS"), dds.domain_id, context.describe_transport(), context.identity(),
                 netmc::dds::time_base_name(time_base), scheduling_outcome.describe());
    // This thread serves management clients and browsers: their work, however much they ask,
    // must not hold a CPU against the job threads and DDS threads at the same SCHED_FIFO priority.
    if (scheduling.fifo_priority > 0 && !netmc::realtime::leave_realtime_scheduling()) {
      spdlog::warn("the management and console thread could not leave SCHED_FIFO: their work competes with the loops");
    }
    io.run();
    return 0;
  } catch (const std::invalid_argument& e) {
    spdlog::error("{}", e.what());
    return 2;
  } catch (const std::exception& e) {
    spdlog::critical("{}", e.what());
    return 1;
  }
}
