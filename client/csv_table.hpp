#pragma once
// A CSV file with a header row, read whole: the outputs of `netmc sim --csv` and
// `netmc sweep --csv` for `netmc plot`. Quoted fields ("a,b", "say ""x""") are understood.

#include <string>
#include <vector>

namespace netmc::cli {

class CsvTable {
 public:
  // Throws std::invalid_argument naming the file (and line) when it cannot be read or a row
  // has the wrong number of fields.
  static CsvTable read(const std::string& path);
  static CsvTable parse(const std::string& text, const std::string& origin);

  const std::vector<std::string>& header() const { return header_; }
  std::size_t rows() const { return rows_.size(); }
  // Index of a column; throws std::invalid_argument "<origin>: no column '<name>'".
  std::size_t column(const std::string& name) const;
  bool has_column(const std::string& name) const;
  const std::string& text(std::size_t row, std::size_t column) const { return rows_[row][column]; }
  // The field as a number; NaN when empty; throws naming file, line and column otherwise.
  double number(std::size_t row, std::size_t column) const;

 private:
  std::string origin_;
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

}  // namespace netmc::cli
