#include "server/axis/axis_node_link.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "dds_typesPubSubTypes.h"
#include "idl/job.pb.h"
#include "server/dds/topics.hpp"
#include "server/job/job_builder.hpp"

namespace netmc::axis {
namespace {

bool realtime(const AxisNodeConfig& config) { return config.clock == "realtime"; }

std::vector<std::string> axis_partitions(const std::vector<std::string>& axes) {
  std::vector<std::string> out;
  for (const auto& axis : axes) out.push_back(dds::partition_of_axis(axis));
  return out;
}

}  // namespace

AxisNodeLink::AxisNodeLink(dds::DdsContext& context, AxisNodeConfig config)
    : context_(context),
      config_(std::move(config)),
      status_writer_(context.writer(
          context.topic<netmc::dds::NodeStatusPubSubType>(dds::kNodeStatusTopic), dds::Delivery::status)),
      reply_writer_(context.writer(context.topic<netmc::dds::ClockReplyPubSubType>(dds::kClockReplyTopic),
                                   dds::Delivery::stream)),
      probes_(context.reader(context.topic<netmc::dds::ClockProbePubSubType>(dds::kClockProbeTopic),
                             dds::Delivery::stream)),
      // Job control is rare and goes to every node, which drops the others' axes' on the DDS
      // thread. At most a job start per axis waits at a time; 64 as the reader's history had.
      control_intake_(
          [this](const eprosima::fastrtps::rtps::GuidPrefix_t& sender, const netmc::dds::JobControl& control) {
            return hosts(control.axis()) && authentic(sender, control.server(), "job control", control.axis());
          },
          64),
      // A 10 kHz job's 400 ms of setpoints.
      setpoint_intake_([this](const eprosima::fastrtps::rtps::GuidPrefix_t& sender,
                              const netmc::dds::Setpoint& setpoint) { return from_holder_of_job(sender, setpoint); },
                       4096) {
  auto* feedback = context.topic<netmc::dds::FeedbackPubSubType>(
      realtime(config_) ? dds::kRealtimeFeedbackTopic : dds::kLockstepFeedbackTopic);
  auto* events = context.topic<netmc::dds::AxisEventPubSubType>(dds::kAxisEventTopic);
  for (const auto& axis : config_.axes) {
    const std::string partition = dds::partition_of_axis(axis);
    writers_[axis] = {context.writer(feedback, realtime(config_) ? dds::Delivery::stream : dds::Delivery::exchange,
                                     partition),
                      context.writer(events, dds::Delivery::control, partition)};
  }
  // A simulated drive is made with each job, powered up: until the first, that is what it shows.
  for (const auto& axis : config_.axes) {
    if (config_.drives.at(axis).hardware) continue;
    drive_reports_[axis] = {drive::PowerState::switch_on_disabled,
                            static_cast<std::uint16_t>(drive::statusword_bits(drive::PowerState::switch_on_disabled) |
                                                       drive::statusword::remote),
                            0, 0.0, 0.0, ""};
  }
  control_reader_ = context.reader(context.topic<netmc::dds::JobControlPubSubType>(dds::kJobControlTopic),
                                   dds::Delivery::control, {}, &control_intake_);
  // Setpoints in the partitions of this node's axes only: at thousands of cycles a second, a
  // node that were sent every axis's would spend its CPU dropping them. (Fast DDS 2.9's content
  // filters cost more: a dynamic type is built per sample.)
  setpoint_reader_ = context.reader(
      context.topic<netmc::dds::SetpointPubSubType>(realtime(config_) ? dds::kRealtimeSetpointTopic
                                                                      : dds::kLockstepSetpointTopic),
      realtime(config_) ? dds::Delivery::stream : dds::Delivery::exchange, axis_partitions(config_.axes),
      &setpoint_intake_);
  probe_thread_ = std::thread([this] { answer_probes(); });
}

AxisNodeLink::~AxisNodeLink() {
  // No more calls into the intakes.
  context_.remove_reader(setpoint_reader_);
  context_.remove_reader(control_reader_);
  stop_.store(true);
  probe_thread_.join();
  if (refused_) return;  // it never served
  try {
    publish_status(netmc::dds::NODE_LEAVING, "shut down");
  } catch (const std::exception&) {
  }
}

void AxisNodeLink::claim(std::chrono::milliseconds listen) {
  // Only for the claim: a node that kept reading every other node's status would cost every
  // status writer one more reader to serve.
  auto* reader = context_.reader(context_.topic<netmc::dds::NodeStatusPubSubType>(dds::kNodeStatusTopic),
                                 dds::Delivery::status);
  struct Remove {
    dds::DdsContext& context;
    eprosima::fastdds::dds::DataReader* reader;
    ~Remove() { context.remove_reader(reader); }
  } remove{context_, reader};
  dds::SampleReader<netmc::dds::NodeStatus> others(reader);
  const std::set<std::string> mine(config_.axes.begin(), config_.axes.end());
  const auto deadline = std::chrono::steady_clock::now() + listen;
  std::string conflict;
  // The whole window, even after a conflict: by its end the servers have matched this node's
  // status writer, so they hear the refusal too.
  while (auto status = others.take_until(deadline)) {
    if (!conflict.empty() || !dds::sent_by(others.last_sender(), status->participant()) ||
        status->participant() == context_.identity() ||
        status->health() == netmc::dds::NODE_REFUSED || status->health() == netmc::dds::NODE_LEAVING) {
      continue;
    }
    if (status->node() == config_.node) conflict = "the name " + config_.node + " is taken by a live node";
    for (const auto& axis : status->axes()) {
      if (conflict.empty() && mine.count(axis)) {
        conflict = "axis " + axis + " is held by node " + status->node();
      }
    }
  }
  if (conflict.empty()) return;
  publish_status(netmc::dds::NODE_REFUSED, "refused: " + conflict);
  refused_ = true;
  status_writer_->wait_for_acknowledgments(eprosima::fastrtps::Duration_t(1, 0));
  throw NodeRefused(conflict);
}

bool AxisNodeLink::authentic(const eprosima::fastrtps::rtps::GuidPrefix_t& sender, const std::string& server,
                             const char* what, const std::string& axis) {
  if (dds::sent_by(sender, server)) return true;
  ++forged_;
  constexpr std::size_t kMaxForgersLogged = 16;  // forger and kind: a flood of fresh forgers cannot fill the log
  const std::string forger = dds::prefix_text(sender);
  std::lock_guard lock(mutex_);
  if (forgers_logged_.size() < kMaxForgersLogged && forgers_logged_.insert(forger + " " + what).second) {
    spdlog::warn("dropped a forged {} for axis {}: it names server {} but participant {} sent it (its further "
                 "forgeries of the kind are counted, not logged)",
                 what, axis.substr(0, 64), server.substr(0, 32), forger);
  }
  return false;
}

bool AxisNodeLink::obeys(const eprosima::fastrtps::rtps::GuidPrefix_t& sender) {
  if (config_.server_name.empty()) return true;
  const std::string key = dds::prefix_text(sender);
  {
    std::lock_guard lock(mutex_);
    if (const auto it = obeyed_.find(key); it != obeyed_.end()) return it->second;
  }
  const auto identity = context_.participant_identity(sender);
  if (!identity) return false;  // not discovered yet: asked again with its next sample
  // Under DDS Security the certificate must name the server too (make-lab-pki.sh issues
  // CN=NAME); without it the name is the participant's own word.
  const std::string& subject = identity->certificate_subject;
  const std::string cn = "CN=" + config_.server_name;
  const std::size_t at = subject.find(cn);
  const bool certified = subject.empty() || (at != std::string::npos && (at + cn.size() == subject.size() ||
                                                                         subject[at + cn.size()] == ',' ||
                                                                         subject[at + cn.size()] == '/'));
  const bool verdict = identity->name == config_.server_name && certified;
  constexpr std::size_t kMaxVerdicts = 256;
  std::lock_guard lock(mutex_);
  if (obeyed_.size() >= kMaxVerdicts) obeyed_.clear();
  if (!verdict) {
    spdlog::warn("participant {} ('{}'{}) is ignored: this node obeys server '{}' only (--server-name)", key,
                 identity->name.substr(0, 64), subject.empty() ? "" : ", certificate " + subject.substr(0, 96),
                 config_.server_name);
  }
  obeyed_[key] = verdict;
  return verdict;
}

std::optional<netmc::dds::JobControl> AxisNodeLink::take_control() {
  // --server-name's verdict here, not on the receive thread: it needs the sender's discovery
  // data, which may lag its first sample.
  while (auto control = control_intake_.take()) {
    if (obeys(control_intake_.last_sender())) return control;
  }
  return std::nullopt;
}

bool AxisNodeLink::reset_request(const netmc::dds::JobControl& control) const {
  return control.kind() == netmc::dds::CONTROL_FAULT_RESET && hosts(control.axis());
}

bool AxisNodeLink::commissioning_request(const netmc::dds::JobControl& control) const {
  switch (control.kind()) {
    case netmc::dds::CONTROL_ENABLE:
    case netmc::dds::CONTROL_DISABLE:
    case netmc::dds::CONTROL_QUICK_STOP:
    case netmc::dds::CONTROL_MOVE:
    case netmc::dds::CONTROL_JOG:
      return hosts(control.axis());
    default:
      return false;
  }
}

bool AxisNodeLink::from_holder_of_job(const eprosima::fastrtps::rtps::GuidPrefix_t& sender,
                                      const netmc::dds::Setpoint& setpoint) {
  if (!authentic(sender, setpoint.server(), "setpoint", setpoint.axis())) return false;
  std::lock_guard lock(mutex_);
  const auto it = holds_.find(setpoint.axis());
  return it != holds_.end() && it->second.job_id == setpoint.job_id() && it->second.server == setpoint.server();
}

bool AxisNodeLink::hosts(const std::string& axis) const {
  return std::find(config_.axes.begin(), config_.axes.end(), axis) != config_.axes.end();
}

const AxisNodeLink::AxisWriters& AxisNodeLink::writers_of(const std::string& axis) const {
  const auto it = writers_.find(axis);
  if (it == writers_.end()) throw std::invalid_argument("axis " + axis + " is not hosted by this node");
  return it->second;
}

void AxisNodeLink::publish(netmc::dds::Feedback& feedback) {
  dds::write_checked(writers_of(feedback.axis()).feedback, &feedback);
}

void AxisNodeLink::publish_event(netmc::dds::AxisEvent& event) {
  dds::write_checked(writers_of(event.axis()).events, &event);
}

bool AxisNodeLink::held(const Hold& hold, std::chrono::steady_clock::time_point now) const {
  return !hold.server.empty() && now - hold.last_contact < config_.hold_lease;
}

void AxisNodeLink::publish_status(netmc::dds::NodeHealth health, const std::string& detail) {
  netmc::dds::NodeStatus status;
  status.node(config_.node);
  status.axes(config_.axes);
  status.plant(config_.plant);
  status.clock(config_.clock);
  status.time_base(dds::time_base_name(config_.time_base));
  {
    // A latched fault is what the node is, whatever it is doing otherwise.
    std::lock_guard lock(mutex_);
    std::string faults;
    for (const auto& [axis, reason] : faults_) faults += (faults.empty() ? "" : "; ") + axis + ": " + reason;
    // A drive that does not answer, or stands in Fault, cannot start a job: the node says so,
    // naming the drive and the cause.
    std::string drives;
    for (const auto& axis : config_.axes) {
      const auto report = drive_reports_.find(axis);
      if (report == drive_reports_.end() || faults_.count(axis)) continue;
      std::string problem = report->second.unreachable;
      if (problem.empty() && report->second.state == drive::PowerState::fault) {
        problem = "in Fault (error " + drive::describe_error_code(report->second.error_code) + ")";
      }
      if (problem.empty()) continue;
      const auto& drive = config_.drives.at(axis);
      drives += (drives.empty() ? "" : "; ") + axis + ": " +
                (drive.hardware ? drive.hardware->describe() : drive.spec.describe()) + ": " + problem;
    }
    status.health(faults.empty() && drives.empty() ? health : netmc::dds::NODE_FAULT);
    std::string said = faults.empty() ? detail : faults + "; reset with netmc reset (or SIGUSR1 on the axis's host)";
    if (!drives.empty()) said = faults.empty() ? drives : said + "; " + drives;
    if (const auto forged = forged_.load(); forged > 0) said += "; " + std::to_string(forged) + " forged samples dropped";
    if (const auto dropped = setpoint_intake_.dropped(); dropped > 0) {
      said += "; " + std::to_string(dropped) + " setpoints of no job here dropped";
    }
    status.detail(said.substr(0, 255));
    for (const auto& axis : config_.axes) {
      netmc::dds::AxisDriveStatus entry;
      entry.axis(axis);
      const auto& drive = config_.drives.at(axis);
      entry.drive((drive.hardware ? drive.hardware->describe() : drive.spec.describe()).substr(0, 128));
      const auto report = drive_reports_.find(axis);
      const AxisDriveReport seen = report == drive_reports_.end() ? AxisDriveReport{} : report->second;
      // The drive's own state, or that it did not answer (not a state it was not read in).
      entry.state(seen.unreachable.empty() ? drive::power_state_name(seen.state) : "no answer");
      entry.statusword(seen.statusword);
      entry.error_code(seen.error_code);
      entry.fault_latched(faults_.count(axis) > 0);
      if (const auto last = last_faults_.find(axis); last != last_faults_.end()) entry.last_fault(last->second.substr(0, 255));
      entry.limits(drive.limits.describe().substr(0, 255));
      entry.position_m(seen.position_m);
      entry.velocity_m_s(seen.velocity_m_s);
      const auto motion = motion_reports_.find(axis);
      const AxisMotionReport moving = motion == motion_reports_.end() ? AxisMotionReport{} : motion->second;
      entry.motion(moving.motion);
      entry.following_error_m(moving.following_error_m);
      entry.command_number(moving.command_number);
      entry.command_refused(moving.command_refused);
      entry.command_note(moving.command_note.substr(0, 255));
      status.drives().push_back(entry);
    }
  }
  status.server_name(config_.server_name);
  status.participant(context_.identity());
  {
    std::lock_guard lock(mutex_);
    const auto now = std::chrono::steady_clock::now();
    for (const auto& [axis, hold] : holds_) {
      if (!held(hold, now)) continue;
      netmc::dds::AxisHold entry;
      entry.axis(axis);
      entry.server(hold.server);
      entry.job_id(hold.job_id);
      status.holds().push_back(entry);
    }
  }
  status.status_period_s(std::chrono::duration<double>(kStatusPeriod).count());
  dds::write_checked(status_writer_, &status);
}

void AxisNodeLink::refuse(const netmc::dds::JobControl& control, netmc::dds::AxisEventKind kind,
                          const std::string& why) {
  spdlog::warn("job {} of server {} refused: {}", control.job_id(), control.server(), why);
  netmc::dds::AxisEvent event;
  event.axis(control.axis());
  event.server(control.server());
  event.job_id(control.job_id());
  event.iteration(control.iteration());
  event.kind(kind);
  event.detail(why.substr(0, 255));
  publish_event(event);
}

std::string AxisNodeLink::admit(const netmc::dds::JobControl& control) {
  std::lock_guard lock(mutex_);
  const auto now = std::chrono::steady_clock::now();
  Hold& hold = holds_[control.axis()];  // only hosted axes reach here
  const bool new_job = (control.kind() == netmc::dds::CONTROL_BEGIN_ITERATION ||
                        control.kind() == netmc::dds::CONTROL_PREPARE_ITERATION) &&
                       !control.job_spec().empty();
  if (held(hold, now) && hold.server == control.server() && hold.job_id == control.job_id()) {
    hold.last_contact = now;
    return "";
  }
  if (!new_job) return "not the job of the server that holds this axis";
  if (held(hold, now) && hold.server != control.server()) {
    return "axis " + control.axis() + " is held by server " + hold.server + " (job " + std::to_string(hold.job_id) + ")";
  }
  hold = {control.server(), control.job_id(), now};
  return "";
}

bool AxisNodeLink::from_holder(const std::string& axis, const std::string& server, std::uint64_t job_id) {
  std::lock_guard lock(mutex_);
  const auto it = holds_.find(axis);
  if (it == holds_.end() || it->second.server != server || it->second.job_id != job_id) return false;
  it->second.last_contact = std::chrono::steady_clock::now();
  return true;
}

void AxisNodeLink::release(const std::string& axis, const std::string& server, std::uint64_t job_id) {
  std::lock_guard lock(mutex_);
  const auto it = holds_.find(axis);
  if (it != holds_.end() && it->second.server == server && it->second.job_id == job_id) holds_.erase(it);
}

void AxisNodeLink::report_fault(const std::string& axis, JobAxis& job_axis, const std::string& server,
                                std::uint32_t iteration) {
  if (job_axis.fault_reported || !job_axis.endpoint || !job_axis.endpoint->fault()) return;
  job_axis.fault_reported = true;
  const std::string reason = *job_axis.endpoint->fault();
  {
    std::lock_guard lock(mutex_);
    faults_.emplace(axis, reason);
    last_faults_[axis] = reason;
  }
  spdlog::error("axis {} FAULT (job {}): {}; quick stop, then Fault until the operator resets it (netmc reset, "
                "or SIGUSR1 on this host)",
                axis, job_axis.job_id, reason);
  netmc::dds::AxisEvent event;
  event.axis(axis);
  event.server(server);
  event.job_id(job_axis.job_id);
  event.iteration(iteration);
  event.kind(netmc::dds::AXIS_FAULT);
  event.detail(("axis " + axis + " tripped: " + reason).substr(0, 255));
  publish_event(event);
  publish_status(netmc::dds::NODE_FAULT, "");
}

std::vector<std::string> AxisNodeLink::reset_faults(const std::vector<std::string>& axes) {
  std::vector<std::string> reset;
  {
    std::lock_guard lock(mutex_);
    for (auto it = faults_.begin(); it != faults_.end();) {
      if (axes.empty() || std::find(axes.begin(), axes.end(), it->first) != axes.end()) {
        reset.push_back(it->first);
        it = faults_.erase(it);
      } else {
        ++it;
      }
    }
  }
  if (reset.empty()) return reset;
  std::string names;
  for (const auto& axis : reset) names += (names.empty() ? "" : ",") + axis;
  spdlog::info("faults of axes {} reset by the operator", names);
  publish_status(netmc::dds::NODE_IDLE, "ready (faults reset)");
  return reset;
}

std::atomic<bool>& fault_reset_requested() {
  static std::atomic<bool> requested{false};
  return requested;
}

std::vector<std::string> AxisNodeLink::poll_fault_reset() {
  if (!fault_reset_requested().exchange(false)) return {};
  return reset_faults();
}

bool AxisNodeLink::faulted() const {
  std::lock_guard lock(mutex_);
  return !faults_.empty();
}

bool AxisNodeLink::faulted(const std::string& axis) const {
  std::lock_guard lock(mutex_);
  return faults_.count(axis) > 0;
}

void AxisNodeLink::report_drive(const std::string& axis, drive::PowerState state,
                                const drive::DriveFeedback& feedback) {
  std::lock_guard lock(mutex_);
  drive_reports_[axis] = {state, feedback.statusword, feedback.error_code, feedback.position_m, feedback.velocity_m_s, ""};
}

void AxisNodeLink::report_unreachable(const std::string& axis, const std::string& cause) {
  std::lock_guard lock(mutex_);
  auto& report = drive_reports_[axis];
  report = AxisDriveReport{};
  report.unreachable = cause.empty() ? "no answer" : cause;
}

std::string AxisNodeLink::drive_problem(const std::string& axis) const {
  std::lock_guard lock(mutex_);
  const auto report = drive_reports_.find(axis);
  if (report == drive_reports_.end()) return "";
  if (!report->second.unreachable.empty()) return report->second.unreachable;
  if (report->second.state == drive::PowerState::fault && !faults_.count(axis)) {
    return "the drive is in Fault (error " + drive::describe_error_code(report->second.error_code) + ")";
  }
  return "";
}

void AxisNodeLink::report_motion(const std::string& axis, const std::string& motion, double following_error_m) {
  std::lock_guard lock(mutex_);
  auto& report = motion_reports_[axis];
  report.motion = motion;
  report.following_error_m = following_error_m;
}

void AxisNodeLink::report_command(const std::string& axis, std::uint64_t number, bool refused,
                                  const std::string& note) {
  std::lock_guard lock(mutex_);
  auto& report = motion_reports_[axis];
  report.command_number = number;
  report.command_refused = refused;
  report.command_note = note;
}

bool AxisNodeLink::server_reads(const netmc::dds::JobControl& begin) const {
  const AxisWriters& writers = writers_of(begin.axis());
  return context_.matches_participants(writers.feedback, {begin.server()}) &&
         context_.matches_participants(writers.events, {begin.server()});
}

bool AxisNodeLink::linked_to_server(const netmc::dds::JobControl& begin) const {
  return server_reads(begin) && context_.matches_participants(setpoint_reader_, {begin.server()});
}

std::string AxisNodeLink::why_not_linked(const netmc::dds::JobControl& begin) const {
  const std::string server = begin.server().substr(0, 32);
  if (!server_reads(begin)) return "server " + server + " does not read this node's feedback";
  return "this node does not hear the setpoints of server " + server;
}

JobAxis AxisNodeLink::start_job(const netmc::dds::JobControl& begin) {
  {
    std::lock_guard lock(mutex_);
    if (const auto it = faults_.find(begin.axis()); it != faults_.end()) {
      throw std::runtime_error("axis " + begin.axis() + " is in fault (" + it->second +
                               "); its operator resets it: netmc reset " + config_.node + " (or SIGUSR1 on its host)");
    }
  }
  if (const std::string problem = drive_problem(begin.axis()); !problem.empty()) {
    throw std::runtime_error("axis " + begin.axis() + " is in fault: its drive " +
                             config_.drives.at(begin.axis()).hardware->describe() + ": " + problem +
                             "; netmc reset " + config_.node + " once the cause is gone");
  }
  // The server must read this node's feedback before the first sample leaves, and its setpoints
  // must reach this node before the first one is due.
  if (!linked_to_server(begin)) throw std::runtime_error(why_not_linked(begin));
  netmc::v1::JobSpec spec;
  if (!spec.ParseFromArray(begin.job_spec().data(), static_cast<int>(begin.job_spec().size()))) {
    throw std::invalid_argument("malformed job spec");
  }
  job::reject_file_references(spec);  // a node opens no path a sample names
  if (spec.plant() != config_.plant) {
    throw std::invalid_argument("the job needs plant '" + spec.plant().substr(0, 64) + "', this node hosts '" +
                                config_.plant + "'");
  }
  const AxisDrive& axis_drive = config_.drives.at(begin.axis());
  // The node's plant (its own --plant, equal to the job's) is built here; the controller runs on
  // the server and a plugin's file is not opened here.
  job::JobBuildOptions build;
  build.controller_plugins.load = false;
  const sim::ContourJob job = job::build_contour_job(with_node_overrides(spec, begin.axis(), axis_drive), build);
  const auto job_axes = job::axis_names(spec);
  const auto it = std::find(job_axes.begin(), job_axes.end(), begin.axis());
  if (it == job_axes.end()) throw std::invalid_argument("axis " + begin.axis() + " is not an axis of the job");
  const auto index = static_cast<std::size_t>(it - job_axes.begin());
  JobAxis axis;
  axis.endpoint = std::make_unique<sim::AxisEndpoint>(job_drive(axis_drive, job, index, config_.drive_settings), job,
                                                      index, axis_drive.limits);
  axis.endpoint->follow_job_reference(job);
  axis.job_id = begin.job_id();
  axis.cycles = job.cycles();
  axis.sample_period_s = job.sample_period_s;
  return axis;
}

void AxisNodeLink::answer_probes() {
  while (!stop_.load()) {
    auto received = probes_.take_until_received(std::chrono::steady_clock::now() + std::chrono::milliseconds(100));
    if (!received || received->first.node() != config_.node ||
        !authentic(probes_.last_sender(), received->first.server(), "clock probe", "-")) {
      continue;
    }
    const auto* probe = &received->first;
    netmc::dds::ClockReply reply;
    reply.t2_s(dds::time_base_at_s(config_.time_base, received->second));
    reply.server(probe->server());
    reply.node(config_.node);
    reply.number(probe->number());
    reply.t1_s(probe->t1_s());
    reply.t3_s(now_s());
    try {
      dds::write_checked(reply_writer_, &reply);
    } catch (const std::exception&) {
      // A reply that cannot leave is a lost probe: the server's estimate uses the others.
    }
  }
}

double planned_instant(const netmc::dds::Setpoint& setpoint) {
  const double acts_at = setpoint.acts_at_s();
  return std::isfinite(acts_at) && acts_at > 0.0 ? acts_at : -std::numeric_limits<double>::infinity();
}

void submit_to(sim::AxisEndpoint& endpoint, double send_time_s, const netmc::dds::Setpoint& setpoint) {
  if (setpoint.horizon().empty()) {
    endpoint.submit_setpoint(send_time_s, setpoint.cycle(), setpoint.command(), planned_instant(setpoint));
    return;
  }
  // A packet's instant is on the job's grid, 0 included; one that is no time plays on arrival.
  const double acts_at = setpoint.acts_at_s();
  endpoint.submit_packet(send_time_s, setpoint.cycle(),
                         std::isfinite(acts_at) ? acts_at : -std::numeric_limits<double>::infinity(),
                         std::vector<double>(setpoint.horizon().begin(), setpoint.horizon().end()));
}

netmc::dds::AppliedSetpoint applied_entry(const sim::AppliedSetpoint& applied) {
  netmc::dds::AppliedSetpoint entry;
  entry.cycle(applied.sequence);
  entry.send_time_s(applied.send_time_s);
  entry.arrival_time_s(applied.arrival_time_s);
  entry.network_arrival_s(applied.network_arrival_s);
  entry.horizon_index(applied.horizon_index);
  return entry;
}

void append_applied(netmc::dds::Feedback& feedback, const std::vector<sim::AppliedSetpoint>& applied) {
  for (const auto& a : applied) {
    if (feedback.applied().size() >= netmc::dds::kMaxApplied) break;
    feedback.applied().push_back(applied_entry(a));
  }
}

void set_sample(netmc::dds::Feedback& feedback, std::uint64_t cycle, double time_s,
                const sim::AxisSample& sample) {
  feedback.cycle(cycle);
  feedback.kind(netmc::dds::FEEDBACK_SAMPLE);
  feedback.position_m(sample.measured_m);
  feedback.true_position_m(sample.true_position_m);
  feedback.sample_time_s(time_s);
}

std::vector<std::string> parse_axis_list(const std::string& text) {
  std::vector<std::string> names;
  std::string name;
  for (char c : text + ",") {
    if (c != ',') {
      name += c;
      continue;
    }
    job::check_name(name, "--axes");
    if (std::find(names.begin(), names.end(), name) != names.end()) {
      throw std::invalid_argument("--axes: axis '" + name + "' named twice");
    }
    names.push_back(name);
    name.clear();
  }
  if (names.size() > netmc::dds::kMaxAxesPerNode) throw std::invalid_argument("--axes: at most 64 axes per node");
  return names;
}

}  // namespace netmc::axis
