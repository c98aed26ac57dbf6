#include "client/csv_table.hpp"

#include <charconv>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace netmc::cli {
namespace {

std::vector<std::string> split_record(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else if (c != '\r') {
      fields.back() += c;
    }
  }
  return fields;
}

}  // namespace

CsvTable CsvTable::read(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw std::invalid_argument(path + ": cannot read the file");
  std::ostringstream content;
  content << file.rdbuf();
  return parse(content.str(), path);
}

CsvTable CsvTable::parse(const std::string& text, const std::string& origin) {
  CsvTable table;
  table.origin_ = origin;
  std::istringstream stream(text);
  std::size_t line_number = 0;
  for (std::string line; std::getline(stream, line);) {
    ++line_number;
    if (line.empty() || line == "\r") continue;
    auto fields = split_record(line);
    if (table.header_.empty()) {
      table.header_ = std::move(fields);
      continue;
    }
    if (fields.size() != table.header_.size()) {
      throw std::invalid_argument(origin + ":" + std::to_string(line_number) + ": expected " +
                                  std::to_string(table.header_.size()) + " fields, got " +
                                  std::to_string(fields.size()));
    }
    table.rows_.push_back(std::move(fields));
  }
  if (table.header_.empty()) throw std::invalid_argument(origin + ": empty (expected a header row)");
  return table;
}

bool CsvTable::has_column(const std::string& name) const {
  for (const auto& column : header_) {
    if (column == name) return true;
  }
  return false;
}

std::size_t CsvTable::column(const std::string& name) const {
  for (std::size_t i = 0; i < header_.size(); ++i) {
    if (header_[i] == name) return i;
  }
  throw std::invalid_argument(origin_ + ": no column '" + name + "'");
}

double CsvTable::number(std::size_t row, std::size_t column) const {
  const std::string& field = rows_.at(row).at(column);
  if (field.empty()) return std::numeric_limits<double>::quiet_NaN();
  double value = 0.0;
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
  if (error != std::errc() || end != field.data() + field.size()) {
    throw std::invalid_argument(origin_ + ": row " + std::to_string(row + 1) + ", column '" +
                                header_.at(column) + "': expected a number, got '" + field + "'");
  }
  return value;
}

}  // namespace netmc::cli
