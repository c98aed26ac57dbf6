#include "server/service/job_service.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "dds_typesPubSubTypes.h"
#include "server/service/error_response.hpp"

namespace netmc::service {
namespace {

// A job's cancel token has 64 characters; a longer one is refused before it is compared.
constexpr std::size_t kMaxCancelTokenBytes = 256;

const char* health_name(netmc::dds::NodeHealth health) {
  switch (health) {
    case netmc::dds::NODE_IDLE: return "idle";
    case netmc::dds::NODE_RUNNING: return "running";
    case netmc::dds::NODE_HOLD: return "hold";
    case netmc::dds::NODE_FAULT: return "fault";
    case netmc::dds::NODE_REFUSED: return "refused";
    case netmc::dds::NODE_LEAVING: return "leaving";
  }
  return "unknown";
}

}  // namespace

JobService::JobService(dds::DdsContext& context, NodeDirectory& nodes, ClockTracker& clocks,
                       JobServiceOptions options)
    : context_(context),
      nodes_(nodes),
      clocks_(clocks),
      options_(std::move(options)),
      registry_(options_),
      executor_(context, nodes, clocks, registry_, options_),
      scheduler_(registry_, executor_, options_),
      next_command_number_(static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::milliseconds>(
                                                          std::chrono::system_clock::now().time_since_epoch())
                                                          .count())) {}

JobService::~JobService() {
  scheduler_.stop();
  // The writes of the jobs' ends, and what follows them (answers to clients), refer to this. A
  // store that cannot be written is waited for briefly: its ends were told to no one, and a
  // restart reads those jobs as it last kept them.
  if (options_.store) options_.store->flush(std::chrono::seconds(3));
}

void JobService::handle(const std::shared_ptr<management::Peer>& session,
                        const netmc::v1::Request& request, bool admin) {
  netmc::v1::Response response;
  response.set_request_id(request.request_id());
  switch (request.kind_case()) {
    case netmc::v1::Request::kSubmit:
      if (const auto refusal = scheduler_.submit(session, request)) {
        session->send(error_response(request.request_id(), *refusal));
      }
      return;
    case netmc::v1::Request::kCancel: {
      std::lock_guard lock(registry_.mutex());
      const auto held = registry_.find(request.cancel().job_id());
      if (!held) {
        session->send(error_response(request.request_id(),
                                     "cancel: no job " + std::to_string(request.cancel().job_id())));
        return;
      }
      const std::string& presented = request.cancel().cancel_token();
      if (presented.size() > kMaxCancelTokenBytes) {
        session->send(error_response(request.request_id(), "cancel: the job token is longer than " +
                                                               std::to_string(kMaxCancelTokenBytes) + " bytes"));
        return;
      }
      const bool submitter = held->session.lock() == session;
      const bool token_shown = !presented.empty() && held->cancel_token && held->cancel_token->accepts(presented);
      if (!admin && !submitter && !token_shown) {
        session->send(error_response(
            request.request_id(),
            "cancel: job " + std::to_string(held->id) + " was submitted on another connection" +
                (presented.empty() ? "" : " and the job token shown is not its token") +
                "; cancel it with its job token (netmc submit saved it for the user who submitted it, where netmc "
                "cancel finds it; or name the file with --job-token-file), or with the server's admin token "
                "(netmc-server --admin-token-file FILE; the client names FILE in NETMC_TOKEN_FILE)"));
        return;
      }
      Job& job = *held;
      job.cancel_reason = submitter     ? "cancelled by its client"
                          : token_shown ? "cancelled with its job token (netmc cancel)"
                                        : "cancelled by an admin (netmc cancel)";
      job.cancel.store(true);
      scheduler_.drop_if_queued(held);
      *response.mutable_status()->add_jobs() = job.status;
      break;
    }
    case netmc::v1::Request::kStatus: {
      std::lock_guard lock(registry_.mutex());
      for (const auto& [id, job] : registry_.jobs()) {
        if (request.status().job_id() == 0 || request.status().job_id() == id) {
          *response.mutable_status()->add_jobs() = job->status;
        }
      }
      break;
    }
    case netmc::v1::Request::kWatch: {
      std::lock_guard lock(registry_.mutex());
      const auto held = registry_.find(request.watch().job_id());
      if (!held) {
        session->send(error_response(request.request_id(),
                                     "watch: no job " + std::to_string(request.watch().job_id()) +
                                         " (never submitted, or ended more than " +
                                         std::to_string(options_.job_history) +
                                         " jobs ago: netmc jobs lists the server's history)"));
        return;
      }
      registry_.start_watch(*held, session, request.request_id());
      return;
    }
    case netmc::v1::Request::kNodes: {
      const auto now = std::chrono::steady_clock::now();
      auto& reply = *response.mutable_nodes();
      reply.set_server(context_.identity());
      reply.set_expiry_s(std::chrono::duration<double>(nodes_.expiry()).count());
      for (const auto& record : nodes_.nodes()) fill_node_info(record, now, *reply.add_nodes());
      break;
    }
    case netmc::v1::Request::kReset: {
      const auto& reset = request.reset();
      if (!admin && options_.admin_token_configured) {
        session->send(error_response(request.request_id(),
                                     "reset: needs the admin token (the file of netmc-server --admin-token-file, "
                                     "named to the client by NETMC_TOKEN_FILE)"));
        return;
      }
      const std::optional<NodeRecord> target = find_node(reset.node());
      if (!target) {
        session->send(error_response(request.request_id(), "reset: no node '" + reset.node().substr(0, 64) +
                                                               "' (netmc nodes lists the nodes this server sees)"));
        return;
      }
      std::vector<std::string> axes(reset.axes().begin(), reset.axes().end());
      for (const auto& axis : axes) {
        const auto& hosted = target->status.axes();
        if (std::find(hosted.begin(), hosted.end(), axis) == hosted.end()) {
          session->send(error_response(request.request_id(), "reset: node " + reset.node() + " hosts no axis '" +
                                                                 axis.substr(0, 64) + "'"));
          return;
        }
      }
      if (axes.empty()) axes.assign(target->status.axes().begin(), target->status.axes().end());
      try {
        for (const auto& axis : axes) {
          netmc::dds::JobControl control;
          control.axis(axis);
          control.server(context_.identity());
          control.kind(netmc::dds::CONTROL_FAULT_RESET);
          dds::write_checked(executor_.control(), &control);
        }
      } catch (const std::exception& error) {
        session->send(error_response(request.request_id(), std::string("reset: ") + error.what()));
        return;
      }
      spdlog::info("fault reset of node {} ({} axes) sent{}", reset.node(), axes.size(), admin ? " by an admin" : "");
      auto& reply = *response.mutable_reset();
      reply.set_server(context_.identity());
      reply.set_expiry_s(std::chrono::duration<double>(nodes_.expiry()).count());
      fill_node_info(*target, std::chrono::steady_clock::now(), *reply.add_nodes());
      break;
    }
    case netmc::v1::Request::kAxisCommand:
      command_axis(session, request, admin);
      return;
    case netmc::v1::Request::kJobs:
      try {
        *response.mutable_jobs() = registry_.list_jobs(request.jobs());
      } catch (const std::exception& error) {
        session->send(error_response(request.request_id(), std::string("jobs: ") + error.what()));
        return;
      }
      break;
    case netmc::v1::Request::KIND_NOT_SET:
      session->send(error_response(request.request_id(),
                                   "request: empty (expected submit, cancel, status, watch, nodes, reset, jobs or axis_command)"));
      return;
  }
  session->send(response);
}

ServiceTotals JobService::totals() const { return registry_.totals(); }

std::optional<NodeRecord> JobService::find_node(const std::string& name) const {
  for (auto& record : nodes_.nodes()) {
    if (record.status.node() == name) return std::move(record);
  }
  return std::nullopt;
}

void JobService::command_axis(const std::shared_ptr<management::Peer>& session, const netmc::v1::Request& request,
                              bool admin) {
  const auto& command = request.axis_command();
  const auto refuse = [&](const std::string& why) { session->send(error_response(request.request_id(), why)); };
  using Kind = netmc::v1::AxisCommand;
  const char* verb = command.kind() == Kind::ENABLE       ? "enable"
                     : command.kind() == Kind::DISABLE    ? "disable"
                     : command.kind() == Kind::QUICK_STOP ? "quick-stop"
                     : command.kind() == Kind::MOVE       ? "move"
                     : command.kind() == Kind::JOG        ? "jog"
                                                          : nullptr;
  if (!verb) return refuse("axis_command.kind: expected ENABLE, DISABLE, QUICK_STOP, MOVE or JOG");
  const std::string what = std::string(verb) + ": ";
  if (!admin && options_.admin_token_configured) {
    return refuse(what + "needs the admin token (the file of netmc-server --admin-token-file, named to the client by "
                         "NETMC_TOKEN_FILE)");
  }
  if (!std::isfinite(command.target_m()) || !std::isfinite(command.speed_m_s())) {
    return refuse(what + "the target and the speed must be finite numbers (m, m/s)");
  }
  const std::optional<NodeRecord> target = find_node(command.node());
  if (!target) {
    return refuse(what + "no node '" + command.node().substr(0, 64) + "' (netmc nodes lists the nodes this server sees)");
  }
  const auto& hosted = target->status.axes();
  std::vector<std::string> axes;
  if (command.axis().empty()) {
    if (command.kind() == Kind::MOVE || command.kind() == Kind::JOG) return refuse(what + "names one axis");
    axes.assign(hosted.begin(), hosted.end());
  } else if (std::find(hosted.begin(), hosted.end(), command.axis()) == hosted.end()) {
    return refuse(what + "node " + command.node() + " hosts no axis '" + command.axis().substr(0, 64) + "'");
  } else {
    axes.push_back(command.axis());
  }
  // A job's axes move only by its commands; its operator stops them (quick stop) or cancels it.
  if (command.kind() != Kind::QUICK_STOP) {
    for (const auto& hold : target->status.holds()) {
      if (std::find(axes.begin(), axes.end(), hold.axis()) == axes.end()) continue;
      const bool ours = hold.server() == context_.identity();
      return refuse(what + "axis " + hold.axis() + " is held by job " + std::to_string(hold.job_id()) + " of " +
                    (ours ? "this server: cancel it first (netmc cancel " + std::to_string(hold.job_id()) + ")"
                          : "server " + hold.server() + ": it moves only by that job's commands"));
    }
  }
  const std::uint64_t number = next_command_number_.fetch_add(1);
  try {
    for (const auto& axis : axes) {
      netmc::dds::JobControl control;
      control.axis(axis);
      control.server(context_.identity());
      control.job_id(number);
      control.kind(command.kind() == Kind::ENABLE       ? netmc::dds::CONTROL_ENABLE
                   : command.kind() == Kind::DISABLE    ? netmc::dds::CONTROL_DISABLE
                   : command.kind() == Kind::QUICK_STOP ? netmc::dds::CONTROL_QUICK_STOP
                   : command.kind() == Kind::MOVE       ? netmc::dds::CONTROL_MOVE
                                                        : netmc::dds::CONTROL_JOG);
      control.start_position_m(command.target_m());
      control.speed_m_s(command.speed_m_s());
      dds::write_checked(executor_.control(), &control);
    }
  } catch (const std::exception& error) {
    return refuse(what + error.what());
  }
  if (command.kind() != Kind::JOG) {
    spdlog::info("{} of node {} ({}) sent{}", verb, command.node(), command.axis().empty() ? "every axis" : command.axis(),
                 admin ? " by an admin" : "");
  }
  netmc::v1::Response response;
  response.set_request_id(request.request_id());
  auto& sent = *response.mutable_axis_command();
  sent.set_command_number(number);
  fill_node_info(*target, std::chrono::steady_clock::now(), *sent.mutable_node());
  session->send(response);
}

void JobService::fill_node_info(const NodeRecord& record, std::chrono::steady_clock::time_point now,
                                netmc::v1::NodeInfo& info) const {
  info.set_node(record.status.node());
  for (const auto& axis : record.status.axes()) info.add_axes(axis);
  info.set_plant(record.status.plant());
  const std::string health = record.refused.empty() ? health_name(record.status.health()) : "refused";
  const std::string detail = record.refused.empty() ? record.status.detail() : record.refused;
  info.set_health(health + (detail.empty() ? "" : ": " + detail));
  info.set_last_seen_s(std::chrono::duration<double>(now - record.last_seen).count());
  info.set_clock(record.status.clock());
  info.set_time_base(record.status.time_base());
  info.set_participant(record.status.participant());
  std::string holders;
  for (const auto& hold : record.status.holds()) {
    // This server by a name, another by its participant's GUID prefix (all a node knows of it).
    const std::string server = hold.server() == context_.identity() ? "this server" : hold.server();
    holders += (holders.empty() ? "" : ", ") + server + " (job " + std::to_string(hold.job_id()) + ", axis " +
               hold.axis() + ")";
  }
  info.set_held_by(holders);
  if (const auto clock = clocks_.estimate(record.status.node())) {
    info.set_clock_measured(true);
    info.set_clock_offset_s(clock->offset_s);
    info.set_round_trip_s(clock->round_trip_s);
  }
  for (const auto& drive : record.status.drives()) {
    auto& entry = *info.add_drives();
    entry.set_axis(drive.axis());
    entry.set_drive(drive.drive());
    entry.set_state(drive.state());
    entry.set_statusword(drive.statusword());
    entry.set_error_code(drive.error_code());
    entry.set_fault_latched(drive.fault_latched());
    entry.set_last_fault(drive.last_fault());
    entry.set_limits(drive.limits());
    entry.set_motion(drive.motion());
    entry.set_position_m(drive.position_m());
    entry.set_velocity_m_s(drive.velocity_m_s());
    entry.set_following_error_m(drive.following_error_m());
    entry.set_command_number(drive.command_number());
    entry.set_command_note(drive.command_note());
    entry.set_command_refused(drive.command_refused());
    const auto events = nodes_.axis_events(record.status.node(), drive.axis());
    entry.set_trips(events.trips);
    entry.set_quick_stops(events.quick_stops);
  }
  info.set_server_name(record.status.server_name());
}

}  // namespace netmc::service
