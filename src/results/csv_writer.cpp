#include "results/csv_writer.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>
#include <unordered_set>
#include <utility>

#include "core/validation.hpp"

namespace peg3d::results {
namespace {

std::string joined(const std::vector<std::string>& columns) {
  std::string text;
  for (const std::string& column : columns) text += (text.empty() ? "" : ", ") + column;
  return text;
}

}  // namespace

std::string format_csv_double(double value) {
  // fmt prints the sign of a NaN ("-nan"), which depends on how the NaN was produced: normalise it.
  if (std::isnan(value)) return "nan";
  return fmt::format("{}", value);
}

std::string quote_csv_field(std::string_view field) {
  if (field.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(field);
  std::string quoted = "\"";
  for (char c : field) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  quoted += '"';
  return quoted;
}

CsvWriter::CsvWriter(std::ostream& out, std::vector<std::string> columns) : out_(out), columns_(std::move(columns)) {
  if (columns_.empty()) throw InvalidParameter("columns", "[]", "a CSV file needs at least one column");
  std::unordered_set<std::string_view> seen;
  for (const std::string& column : columns_) {
    if (!seen.insert(column).second) {
      throw InvalidParameter("columns", joined(columns_), fmt::format("column '{}' appears twice", column));
    }
  }
  std::string header;
  for (const std::string& column : columns_) {
    if (!header.empty()) header += ',';
    header += quote_csv_field(column);
  }
  header += '\n';
  out_ << header;
}

CsvWriter::Row& CsvWriter::Row::add_formatted(std::string_view cell) {
  if (cells_ > 0) line_ += ',';
  line_ += cell;
  ++cells_;
  return *this;
}

CsvWriter::Row& CsvWriter::Row::add(std::string_view text) { return add_formatted(quote_csv_field(text)); }

CsvWriter::Row& CsvWriter::Row::add(bool value) { return add_formatted(value ? "true" : "false"); }

CsvWriter::Row& CsvWriter::Row::add(double value) { return add_formatted(format_csv_double(value)); }

void CsvWriter::Row::end() {
  if (ended_) throw std::logic_error("CsvWriter::Row::end() called twice");
  const std::vector<std::string>& columns = writer_->columns_;
  if (cells_ != columns.size()) {
    throw InvalidParameter("row cells", std::to_string(cells_),
                           fmt::format("a row needs one cell per column ({}: {})", columns.size(), joined(columns)));
  }
  // A lone empty field would be a blank line, which readers skip: quote it.
  if (line_.empty()) line_ = "\"\"";
  line_ += '\n';
  writer_->out_ << line_;
  ++writer_->rows_;
  ended_ = true;
}

}  // namespace peg3d::results
