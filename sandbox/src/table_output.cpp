#include "table_output.hpp"

#include <cstdio>
#include <stdexcept>

namespace sandbox {
namespace {

std::string quoted(const std::string& cell) {
  if (cell.find_first_of(",\"\n") == std::string::npos) return cell;
  std::string out = "\"";
  for (char ch : cell) {
    if (ch == '"') out += '"';
    out += ch;
  }
  out += '"';
  return out;
}

std::string line(const std::vector<std::string>& cells) {
  std::string out;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i > 0) out += ',';
    out += quoted(cells[i]);
  }
  out += '\n';
  return out;
}

}  // namespace

CsvTable::CsvTable(std::vector<std::string> columns) : columns_(std::move(columns)) {}

void CsvTable::addRow(const std::vector<std::string>& cells) {
  if (cells.size() != columns_.size()) throw std::logic_error("CsvTable: row width differs from the header");
  rows_.push_back(cells);
}

std::string CsvTable::text() const {
  std::string out = line(columns_);
  for (const auto& row : rows_) out += line(row);
  return out;
}

std::string CsvTable::number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

std::string CsvTable::fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

}  // namespace sandbox
