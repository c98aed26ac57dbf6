// netmc._core: the compiled half of the Python package (python/netmc). It parses the keyword
// flags of netmc.sim() and netmc.sweep() with the command line's own parser (client/sim_command,
// client/sweep_command), runs the same study in-process with the GIL released, and hands back
// the JSON the CLI writes and the per-cycle traces as numpy arrays (no file in between).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <spdlog/spdlog.h>

#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "client/sim_command.hpp"
#include "client/sweep_command.hpp"
#include "client/sweep_shard.hpp"
#include "server/job/job_builder.hpp"
#include "server/sim/contour_job_runner.hpp"

namespace py = pybind11;

namespace netmc::python {
namespace {

// Parses `arguments` (flags after the command's name) as `netmc COMMAND` would; a bad flag
// raises ValueError with the CLI's own message.
void parse(CLI::App& root, const std::string& command, const std::vector<std::string>& arguments) {
  std::vector<const char*> argv{"netmc", command.c_str()};
  for (const auto& argument : arguments) argv.push_back(argument.c_str());
  try {
    root.parse(static_cast<int>(argv.size()), argv.data());
  } catch (const CLI::ParseError& error) {
    throw std::invalid_argument(error.what());
  }
}

CLI::App* command_app(CLI::App& root, const std::string& command, cli::SimFlags& sim, cli::SweepFlags& sweep) {
  if (command == "sim") return cli::add_sim_flags(root, sim);
  if (command == "sweep") return cli::add_sweep_flags(root, sweep).sweep;
  throw std::invalid_argument("command: expected 'sim' or 'sweep', got '" + command + "'");
}

// The flags of `netmc COMMAND` as the CLI registers them: what netmc.sim(**flags) accepts.
py::list command_flags(const std::string& command) {
  CLI::App root("netmc");
  cli::SimFlags sim;
  cli::SweepFlags sweep;
  CLI::App* app = command_app(root, command, sim, sweep);
  py::list flags;
  for (const CLI::Option* option : app->get_options()) {
    if (option->get_lnames().empty() || option->get_lnames().front() == "help") continue;
    py::dict flag;
    flag["name"] = option->get_lnames().front();
    flag["type_name"] = option->get_type_name();
    flag["description"] = option->get_description();
    flag["takes_value"] = option->get_expected_min() > 0;  // a switch may be given alone
    flag["repeatable"] = option->get_expected_max() > 1;
    flags.append(flag);
  }
  return flags;
}

std::string command_help(const std::string& command) {
  CLI::App root("netmc");
  cli::SimFlags sim;
  cli::SweepFlags sweep;
  return command_app(root, command, sim, sweep)->help();
}

py::array_t<double> to_array(const std::vector<double>& values) {
  py::array_t<double> array(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), array.mutable_data());
  return array;
}

// The per-cycle traces of a study, turned into numpy arrays only when Python asks for one
// iteration's (Study.trace). Recorded during the run (traces="all"), or made on demand: the run is
// deterministic for its seed, so running its job again up to that iteration, recording, gives
// the iteration's own trace (traces="on-demand": the study itself costs what the CLI's does).
class StudyTraces {
 public:
  StudyTraces(std::vector<netmc::v1::JobSpec> jobs, std::vector<cli::RunOutcome> outcomes, bool recorded)
      : jobs_(std::move(jobs)), outcomes_(std::move(outcomes)), recorded_(recorded) {}
  std::size_t iterations(std::size_t run) const {
    return static_cast<std::size_t>(outcomes_.at(run).result.iterations_size());
  }
  bool recorded() const { return recorded_; }
  py::dict columns(std::size_t run, std::size_t iteration) const {
    const auto& outcome = outcomes_.at(run);
    if (iteration >= iterations(run)) throw std::out_of_range("iteration: beyond the run's iterations");
    if (recorded_) return to_columns(outcome.iteration_traces.at(iteration), outcome.estimate_names);
    sim::IterationRecord record;
    {
      py::gil_scoped_release release;
      sim::ContourJob job = job::build_contour_job(jobs_.at(run));
      job.record_traces = true;
      sim::ContourJobRunner runner(std::move(job));
      while (runner.completed_iterations() <= iteration) record = runner.run_iteration();
    }
    return to_columns(record.trace, record.metrics.estimate_names);
  }

 private:
  static py::dict to_columns(const std::vector<sim::CycleTrace>& trace,
                             const std::vector<control::EstimateName>& estimate_names) {
    py::dict columns;
    for (const auto& column : cli::trace_columns(trace, estimate_names)) {
      columns[py::str(column.name)] = to_array(column.values);
    }
    return columns;
  }

  std::vector<netmc::v1::JobSpec> jobs_;
  std::vector<cli::RunOutcome> outcomes_;
  bool recorded_;
};

cli::TraceRecording trace_recording(const std::string& traces) {
  if (traces == "all") return cli::TraceRecording::every_iteration;
  if (traces == "on-demand" || traces == "none") return cli::TraceRecording::none;
  throw std::invalid_argument("traces: expected 'on-demand', 'all' or 'none', got '" + traces.substr(0, 32) + "'");
}

py::dict run_sim(const std::vector<std::string>& arguments, const std::string& traces) {
  const cli::TraceRecording recording = trace_recording(traces);
  CLI::App root("netmc");
  cli::SimFlags flags;
  cli::add_sim_flags(root, flags);
  parse(root, "sim", arguments);
  std::ostringstream report;
  std::optional<cli::SimStudy> study;
  {
    py::gil_scoped_release release;
    study = cli::run_sim(flags, report, recording, true);
  }
  py::dict out;
  out["table"] = report.str();
  if (!study) {
    out["json"] = py::none();
    return out;
  }
  out["json"] = study->json;
  py::list labels;
  for (const auto& outcome : study->outcomes) labels.append(outcome.result.label());
  out["labels"] = labels;
  if (traces == "none") {
    out["traces"] = py::none();
  } else {
    out["traces"] = std::make_shared<StudyTraces>(study->plan.jobs, std::move(study->outcomes),
                                                  recording == cli::TraceRecording::every_iteration);
  }
  return out;
}

// `netmc sweep`'s flags from `arguments` (the parsed values outlive the parser).
cli::SweepFlags parse_sweep(const std::vector<std::string>& arguments) {
  CLI::App root("netmc");
  cli::SweepFlags flags;
  cli::add_sweep_flags(root, flags);
  parse(root, "sweep", arguments);
  return flags;
}

py::dict run_sweep(const std::vector<std::string>& arguments, bool keep_json) {
  const cli::SweepFlags flags = parse_sweep(arguments);
  std::ostringstream report;
  cli::SweepRunOptions options;
  options.keep_csv = true;
  options.keep_json = keep_json;
  options.progress = false;
  options.report = &report;
  cli::SweepStudy study;
  {
    py::gil_scoped_release release;
    study = cli::run_sweep(flags, options);
  }
  py::dict out;
  out["csv"] = study.csv;
  out["json"] = keep_json ? py::object(py::str(study.json)) : py::object(py::none());
  out["summary"] = report.str();
  out["configurations"] = study.configurations;
  out["grid_configurations"] = study.grid_configurations;
  return out;
}

std::size_t sweep_size(const std::vector<std::string>& arguments) {
  return cli::expand_sweep_flags(parse_sweep(arguments)).size();
}

std::string merge_parts(const std::vector<std::pair<std::string, std::string>>& parts) {
  py::gil_scoped_release release;
  return cli::merge_sweep_parts(parts);
}

}  // namespace
}  // namespace netmc::python

PYBIND11_MODULE(_core, module) {
  module.doc() = "netmc's compiled core: the CLI's parser and in-process runner (use the netmc package)";
  // The CLI logs at info; a Python session shows warnings and errors only (netmc.set_log_level).
  spdlog::set_level(spdlog::level::warn);
  module.attr("version") = NETMC_VERSION;
  module.def("command_flags", &netmc::python::command_flags, py::arg("command"));
  module.def("command_help", &netmc::python::command_help, py::arg("command"));
  py::class_<netmc::python::StudyTraces, std::shared_ptr<netmc::python::StudyTraces>>(module, "StudyTraces")
      .def("iterations", &netmc::python::StudyTraces::iterations, py::arg("run"))
      .def("recorded", &netmc::python::StudyTraces::recorded)
      .def("columns", &netmc::python::StudyTraces::columns, py::arg("run"), py::arg("iteration"));
  module.def("sim", &netmc::python::run_sim, py::arg("arguments"), py::arg("traces") = "on-demand");
  module.def("sweep", &netmc::python::run_sweep, py::arg("arguments"), py::arg("keep_json") = false);
  module.def("sweep_size", &netmc::python::sweep_size, py::arg("arguments"));
  module.def("merge_parts", &netmc::python::merge_parts, py::arg("parts"));
  module.def("set_log_level", [](const std::string& level) {
    const auto parsed = spdlog::level::from_str(level);
    if (parsed == spdlog::level::off && level != "off") {
      throw std::invalid_argument("level: expected trace, debug, info, warning, error or off, got '" + level + "'");
    }
    spdlog::set_level(parsed);
  }, py::arg("level"));
}
