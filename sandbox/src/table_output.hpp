#pragma once
// A CSV table (RFC 4180 quoting) for the measurement commands (bench grid, tradeoff, stress).
#include <string>
#include <vector>

namespace sandbox {

class CsvTable {
 public:
  explicit CsvTable(std::vector<std::string> columns);
  /// One row, as many cells as columns (throws std::logic_error otherwise).
  void addRow(const std::vector<std::string>& cells);
  /// The whole table, header first.
  std::string text() const;
  /// A number with 6 significant digits.
  static std::string number(double value);
  /// A number with `decimals` digits after the point (a Markdown table's cell).
  static std::string fixed(double value, int decimals);

 private:
  std::vector<std::string> columns_;
  std::vector<std::vector<std::string>> rows_;
};

}  // namespace sandbox
