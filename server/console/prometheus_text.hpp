#pragma once
// A page in the Prometheus text exposition format (version 0.0.4), built from metric families:
// `# HELP`, `# TYPE`, then one line per sample, families in the order added. Names are checked
// against Prometheus's grammar ([a-zA-Z_:][a-zA-Z0-9_:]* for metrics, [a-zA-Z_][a-zA-Z0-9_]* for
// labels, no label starting with "__"), label values escaped (\\, \", \n), so a node's or an
// axis's name, which arrives from the network, can never break a line or forge a sample. Numbers
// print exactly (shortest round-trip form); NaN and infinities in Prometheus's spelling.

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace netmc::console {

using MetricLabels = std::vector<std::pair<std::string, std::string>>;

enum class MetricType { counter, gauge, summary };

class PrometheusPage {
 public:
  // Starts a family. Throws std::invalid_argument for a name outside the grammar, a family
  // added twice, or a counter not ending in "_total".
  void family(std::string_view name, MetricType type, std::string_view help);
  // A sample of the current family: `suffix` for a summary's "_sum" and "_count" (else empty).
  // Throws std::invalid_argument for a bad label name or a sample outside a family.
  void sample(const MetricLabels& labels, double value, std::string_view suffix = "");
  void sample(double value) { sample({}, value); }

  const std::string& text() const { return text_; }

 private:
  std::string text_;
  std::string current_;
  MetricType current_type_ = MetricType::gauge;
  std::vector<std::string> names_;
};

// The content type Prometheus asks for this format.
inline constexpr std::string_view kPrometheusContentType = "text/plain; version=0.0.4; charset=utf-8";

// A label value as the format writes it between quotes.
std::string escape_label_value(std::string_view value);
// A number as the format writes it.
std::string format_sample_value(double value);

}  // namespace netmc::console
