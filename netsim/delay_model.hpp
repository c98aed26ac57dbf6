#pragma once
// Packet delay models for one link direction: one draw per packet from a caller-owned
// RandomStream, so a run with a given seed is bit-identical. Build models with the make_*
// factories; all parameters are in seconds and validated (std::invalid_argument on bad input).

#include <memory>
#include <string>
#include <vector>

#include "netsim/random_stream.hpp"

namespace netmc::netsim {

class DelayModel {
 public:
  virtual ~DelayModel() = default;
  virtual double next_delay_s(RandomStream& rng) = 0;     // >= 0, one draw per packet
  virtual void reset() {}                                  // back to the initial state (Markov state, trace position)
  virtual std::unique_ptr<DelayModel> clone() const = 0;   // same parameters, initial state
  virtual std::string describe() const = 0;                // e.g. "uniform(0.3 ms, 0.8 ms)"
  virtual double mean_s() const = 0;                       // analytic mean where known (trace: mean of samples; markov: stationary mean)
};

std::unique_ptr<DelayModel> make_no_delay();
std::unique_ptr<DelayModel> make_constant_delay(double delay_s);
std::unique_ptr<DelayModel> make_uniform_delay(double min_s, double max_s);

// Normal(mean, stddev) restricted to [min, max] by rejection sampling; after a bounded number
// of tries (a window far in the tail) the last draw is clamped, so each packet costs bounded time.
// max_s may be +inf. mean_s() is the exact truncated-normal mean.
std::unique_ptr<DelayModel> make_truncated_normal_delay(double mean_s, double stddev_s, double min_s, double max_s);

// Classic Pareto: x_m = scale_s, alpha = shape, P(X > x) = (x_m / x)^alpha for x >= x_m,
// capped at max_s (+inf allowed). mean_s() is the mean of the capped variable (+inf if alpha <= 1, uncapped).
std::unique_ptr<DelayModel> make_pareto_delay(double scale_s, double shape, double max_s);

// Bursty two-state Markov (Gilbert-like) delay: state good/bad, each with its own delay model,
// switch probabilities per packet. Starts in good; each packet draws from the current state's
// model, then the state switches. mean_s() weights the two means by the stationary distribution.
std::unique_ptr<DelayModel> make_markov_delay(std::unique_ptr<DelayModel> good, std::unique_ptr<DelayModel> bad,
                                              double p_good_to_bad, double p_bad_to_good);

// Replays the given delays in order and wraps around; draws nothing from the stream.
std::unique_ptr<DelayModel> make_trace_delay(std::vector<double> delays_s);

// Reads a delay trace (result in seconds). Format:
//   - lines starting with '#' (after optional whitespace) and blank lines are ignored;
//   - an optional header: if the first remaining line's last column is not a number, it is a
//     header, and that column's name sets the unit by its suffix: "_s", "_ms" or "_us"
//     (e.g. "cycle,delay_ms"); any other name means seconds (the default);
//   - every other line is data: its LAST comma-separated column is the delay, >= 0 and finite.
// Throws std::invalid_argument naming file and line ("trace.csv:7: ...") for an unreadable or
// empty file, a non-numeric delay or one outside [0, 60] s; and for a path that is not a regular
// file, a file over 64 MiB or more than 1e6 samples.
std::vector<double> load_delay_trace_csv(const std::string& path);
// A delay trace from a CSV file (load_delay_trace_csv) or from a real network's measurement: the
// output of `ping -D HOST` (or plain ping), recognised by its first line ("PING ...") or a reply
// line ("... bytes from ... time=0.045 ms"). Each reply's round trip times `round_trip_share`
// (default one half, a symmetric path) is one one-way delay, in order; lines without a reply
// (headers, statistics, timeouts: a lost probe) are skipped. Same bounds and errors as the CSV,
// and a share outside (0, 1].
std::vector<double> load_delay_trace(const std::string& path, double round_trip_share = 0.5);

}  // namespace netmc::netsim
