// SPDX-License-Identifier: GPL-2.0-or-later
#include "text_table.h"

#include <cstdio>
#include <stdexcept>

namespace icgp::app {

TextTable& TextTable::text(const std::string& cell) {
  row_.push_back(cell);
  return *this;
}

TextTable& TextTable::number(double value, int decimals) {
  char cell[64];
  std::snprintf(cell, sizeof cell, "%.*f", decimals, value);
  return text(cell);
}

TextTable& TextTable::integer(long long value) { return text(std::to_string(value)); }

TextTable& TextTable::ratio(double value) {
  char cell[64];
  std::snprintf(cell, sizeof cell, "%.2fx", value);
  return text(cell);
}

TextTable& TextTable::percent(double value) {
  char cell[64];
  std::snprintf(cell, sizeof cell, "%.1f%%", value);
  return text(cell);
}

TextTable& TextTable::accuracy(const TrackingSummary& s, int deg_decimals) {
  return number(s.mean_t_mm, 2).number(s.max_t_mm, 2).number(s.mean_r_deg, deg_decimals).number(s.max_r_deg, deg_decimals);
}

void TextTable::end_row() {
  if (row_.size() != columns_.size())
    throw std::logic_error("a table row has " + std::to_string(row_.size()) + " cells for " +
                           std::to_string(columns_.size()) + " columns");
  rows_.push_back(std::move(row_));
  row_.clear();
}

std::string TextTable::line(const std::vector<std::string>& cells) const {
  std::string out;
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    const TableColumn& column = columns_[i];
    const std::size_t width = static_cast<std::size_t>(column.width);
    const std::string padding(cells[i].size() < width ? width - cells[i].size() : 0, ' ');
    if (i > 0) out += ' ';
    out += column.left ? cells[i] + padding : padding + cells[i];
  }
  out.erase(out.find_last_not_of(' ') + 1);  // empty cells at the end leave no blanks
  return out + "\n";
}

void TextTable::print_header() const {
  if (!groups_.empty()) {
    // Each caption spans its columns and the spaces between them, left-aligned.
    std::string out;
    std::size_t first = 0;
    for (const ColumnGroup& group : groups_) {
      std::size_t width = static_cast<std::size_t>(group.n_columns - 1);
      for (int k = 0; k < group.n_columns; ++k) width += static_cast<std::size_t>(columns_.at(first + k).width);
      first += static_cast<std::size_t>(group.n_columns);
      if (!out.empty()) out += ' ';
      out += group.caption + std::string(group.caption.size() < width ? width - group.caption.size() : 0, ' ');
    }
    out.erase(out.find_last_not_of(' ') + 1);
    std::fputs((out + "\n").c_str(), stdout);
  }
  std::vector<std::string> headers;
  for (const TableColumn& column : columns_) headers.push_back(column.header);
  std::fputs(line(headers).c_str(), stdout);
}

void TextTable::print_last_row() const {
  if (!rows_.empty()) std::fputs(line(rows_.back()).c_str(), stdout);
}

void TextTable::print() const {
  print_header();
  for (const std::vector<std::string>& row : rows_) std::fputs(line(row).c_str(), stdout);
}

std::vector<TableColumn> accuracy_columns(int deg_width) {
  return {{"mean mm", 8}, {"max mm", 8}, {"mean deg", deg_width}, {"max deg", deg_width}};
}

std::vector<TableColumn> columns(std::vector<TableColumn> first, const std::vector<std::vector<TableColumn>>& more) {
  for (const std::vector<TableColumn>& list : more) first.insert(first.end(), list.begin(), list.end());
  return first;
}

}  // namespace icgp::app
