#pragma once
// A CSV file the command wrote, read back by a test: its header and every row as numbers.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "support/file_text.hpp"

namespace lagrange::test {

/// The header and the rows of a CSV file; a word in a cell (a status) reads as 0.
struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;

  /// The value in row `row` of column `column`; NaN and a test failure when there is no such
  /// column.
  double at(size_t row, const std::string& column) const {
    for (size_t i = 0; i < header.size(); ++i)
      if (header[i] == column) return rows.at(row).at(i);
    ADD_FAILURE() << "no column " << column;
    return NAN;
  }
  /// The value in the last row.
  double last(const std::string& column) const { return at(rows.size() - 1, column); }
};

inline CsvTable read_csv_table(const std::filesystem::path& path) {
  std::istringstream in(slurp(path));
  CsvTable csv;
  std::string line, field;
  std::getline(in, line);
  for (std::istringstream h(line); std::getline(h, field, ',');) csv.header.push_back(field);
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::vector<double> row;
    for (std::istringstream r(line); std::getline(r, field, ',');)
      row.push_back(std::strtod(field.c_str(), nullptr));
    csv.rows.push_back(row);
  }
  return csv;
}

}  // namespace lagrange::test
