#pragma once
// The standard figures of netmc, as gnuplot Figures plus the data files they read:
//  - from a sim run's saved outputs (results.json + traces/N-LABEL.csv): desired vs actual
//    contour with a zoom panel, contour error vs time per run, e_sum vs iteration (log y),
//    histogram of the loop delay tau, and each adaptive controller's estimates vs time;
//  - from a sweep's CSV: a metric vs the delay's upper bound, mean over seeds with the
//    min-max band, one line per run.

#include <string>
#include <vector>

#include "client/csv_table.hpp"
#include "client/gnuplot.hpp"
#include "idl/job.pb.h"

namespace netmc::cli {

struct SimOutputs {
  netmc::v1::StudyResult study;
  struct Trace {
    std::string label;
    CsvTable table;
  };
  std::vector<Trace> traces;   // last iteration of each run, in run order
};

// File names inside a sim output directory.
inline constexpr const char* kSimResultsFile = "results.json";
inline constexpr const char* kSimTracesDir = "traces";

// Reads DIR/results.json and DIR/traces/*.csv; throws std::invalid_argument naming the file.
SimOutputs load_sim_outputs(const std::string& dir);

// Writes the data files into `data_dir` and returns the figures that plot them.
std::vector<Figure> sim_figures(const SimOutputs& outputs, const std::string& data_dir);
// `metrics`: sweep CSV columns (e_max_m ...); throws std::invalid_argument for an unknown one.
std::vector<Figure> sweep_figures(const CsvTable& sweep, const std::vector<std::string>& metrics,
                                  const std::string& data_dir);

}  // namespace netmc::cli
