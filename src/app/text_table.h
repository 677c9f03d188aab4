// SPDX-License-Identifier: GPL-2.0-or-later
// The result tables the benchmarks print: columns of fixed width under a header line.
#pragma once

#include <string>
#include <vector>

#include "icgp/eval/metrics.h"

namespace icgp::app {

struct TableColumn {
  std::string header;
  int width = 8;      ///< at least; a longer cell widens its line, not the column
  bool left = false;  ///< names read left-aligned, numbers right-aligned
};

/// Consecutive columns under one caption, in a line above the header.
struct ColumnGroup {
  std::string caption;
  int n_columns = 1;
};

/// A table printed to stdout: the header, then each row, one space between columns.
class TextTable {
 public:
  explicit TextTable(std::vector<TableColumn> columns, std::vector<ColumnGroup> groups = {})
      : columns_(std::move(columns)), groups_(std::move(groups)) {}

  /// Appends cells to the row being built, in column order.
  TextTable& text(const std::string& cell);
  TextTable& number(double value, int decimals);
  TextTable& integer(long long value);
  /// A speed ratio: "2.35x".
  TextTable& ratio(double value);
  /// A share in percent: "12.5%".
  TextTable& percent(double value);
  /// The four accuracy columns of accuracy_columns(): mean and max mm, mean and max deg.
  TextTable& accuracy(const TrackingSummary& s, int deg_decimals = 2);
  /// Ends the row being built; it must have a cell for every column.
  void end_row();

  /// The group captions (if any) and the header, then every row.
  void print() const;
  /// For a table printed as its rows come: the captions and the header, then each row as it
  /// ends (print_last_row after end_row).
  void print_header() const;
  void print_last_row() const;

 private:
  std::string line(const std::vector<std::string>& cells) const;

  std::vector<TableColumn> columns_;
  std::vector<ColumnGroup> groups_;
  std::vector<std::vector<std::string>> rows_;
  std::vector<std::string> row_;
};

/// "mean mm", "max mm", "mean deg", "max deg", of widths 8, 8 and `deg_width`.
std::vector<TableColumn> accuracy_columns(int deg_width = 9);

/// `first`, then the columns of each further list, in order.
std::vector<TableColumn> columns(std::vector<TableColumn> first, const std::vector<std::vector<TableColumn>>& more);

}  // namespace icgp::app
