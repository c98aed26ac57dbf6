// The Prometheus text format as /metrics writes it: families in order with HELP and TYPE, label
// values escaped so that a name from the network cannot start a line of its own, numbers exact.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "server/console/prometheus_text.hpp"

namespace netmc::console {
namespace {

TEST(PrometheusPage, WritesFamiliesWithHelpTypeAndSamples) {
  PrometheusPage page;
  page.family("netmc_nodes_up", MetricType::gauge, "Axis nodes.");
  page.sample(2);
  page.family("netmc_iterations_total", MetricType::counter, "Iterations ended.");
  page.sample(40);
  page.family("netmc_loop_delay_seconds", MetricType::summary, "Loop delay.");
  page.sample({{"quantile", "0.5"}}, 0.00055);
  page.sample({}, 1.5, "_sum");
  page.sample({}, 3000, "_count");
  EXPECT_EQ(page.text(),
            "# HELP netmc_nodes_up Axis nodes.\n# TYPE netmc_nodes_up gauge\nnetmc_nodes_up 2\n"
            "# HELP netmc_iterations_total Iterations ended.\n# TYPE netmc_iterations_total counter\n"
            "netmc_iterations_total 40\n"
            "# HELP netmc_loop_delay_seconds Loop delay.\n# TYPE netmc_loop_delay_seconds summary\n"
            "netmc_loop_delay_seconds{quantile=\"0.5\"} 0.00055\nnetmc_loop_delay_seconds_sum 1.5\n"
            "netmc_loop_delay_seconds_count 3000\n");
}

TEST(PrometheusPage, LabelValuesFromTheNetworkCannotBreakALine) {
  PrometheusPage page;
  page.family("netmc_node_up", MetricType::gauge, "Nodes.");
  // A node named to forge a sample of its own.
  page.sample({{"node", "x\"} 1\nnetmc_nodes_up 99\n\\"}}, 1);
  EXPECT_EQ(page.text(), "# HELP netmc_node_up Nodes.\n# TYPE netmc_node_up gauge\n"
                         "netmc_node_up{node=\"x\\\"} 1\\nnetmc_nodes_up 99\\n\\\\\"} 1\n");
  // Exactly one sample line: the forged one is inside the quotes.
  std::size_t lines = 0;
  for (const char c : page.text()) lines += c == '\n';
  EXPECT_EQ(lines, 3u);
}

TEST(PrometheusPage, NumbersAreExactAndSpecialValuesSpelledAsPrometheusDoes) {
  EXPECT_EQ(format_sample_value(0.1), "0.1");
  EXPECT_EQ(std::stod(format_sample_value(1.0 / 3.0)), 1.0 / 3.0);  // round trip
  EXPECT_EQ(format_sample_value(1e-7), "1e-07");
  EXPECT_EQ(format_sample_value(std::numeric_limits<double>::infinity()), "+Inf");
  EXPECT_EQ(format_sample_value(-std::numeric_limits<double>::infinity()), "-Inf");
  EXPECT_EQ(format_sample_value(std::nan("")), "NaN");
}

TEST(PrometheusPage, RefusesWhatPrometheusWouldNotParse) {
  PrometheusPage page;
  EXPECT_THROW(page.sample(1), std::invalid_argument);  // no family yet
  EXPECT_THROW(page.family("1nodes", MetricType::gauge, ""), std::invalid_argument);
  EXPECT_THROW(page.family("nodes-up", MetricType::gauge, ""), std::invalid_argument);
  EXPECT_THROW(page.family("netmc_iterations", MetricType::counter, ""), std::invalid_argument);  // no _total
  page.family("netmc_a", MetricType::gauge, "");
  EXPECT_THROW(page.family("netmc_a", MetricType::gauge, ""), std::invalid_argument);  // twice
  EXPECT_THROW(page.sample({{"__name__", "x"}}, 1), std::invalid_argument);
  EXPECT_THROW(page.sample({{"a-b", "x"}}, 1), std::invalid_argument);
  EXPECT_THROW(page.sample({}, 1, "_sum"), std::invalid_argument);  // not a summary
}

}  // namespace
}  // namespace netmc::console
