#pragma once
// CSV output with a fixed header. The text is a pure function of the values written: doubles print as the
// shortest representation that reads back to the same double, so two runs with the same seed give
// byte-identical files and a diff of two result files shows only real changes.
//
// Format (RFC 4180 with LF line ends): one header line, then one line per row, every line ending in "\n".
// A field is quoted ("...", inner quotes doubled) only when it contains a comma, a quote, CR or LF.
// Integers print in decimal, bools as true / false, doubles via fmt "{}" (0.1, 1e-12, 3, -0, inf, -inf)
// with every NaN as nan (no sign).

#include <concepts>
#include <cstddef>
#include <ostream>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace peg3d::results {

/// Formats one double the way CsvWriter prints it.
std::string format_csv_double(double value);
/// Quotes `field` if RFC 4180 requires it.
std::string quote_csv_field(std::string_view field);

/// Writes CSV rows to a stream the caller owns (e.g. AtomicFile::stream()). Not thread-safe: collect rows
/// per index and write them from one thread, in index order, to keep files deterministic.
class CsvWriter {
 public:
  /// Writes the header at once. Columns must be non-empty and distinct (InvalidParameter otherwise).
  CsvWriter(std::ostream& out, std::vector<std::string> columns);

  /// One row under construction; the line is written by end(), all at once. A Row destroyed without end()
  /// writes nothing (so an exception while filling it leaves no partial line).
  class Row {
   public:
    Row& add(std::string_view text);
    Row& add(const char* text) { return add(std::string_view(text)); }
    Row& add(bool value);
    Row& add(double value);
    Row& add(float value) { return add(static_cast<double>(value)); }
    Row& add(char) = delete;  // a character or a small number? Pass a string or an int.
    template <std::integral T>
      requires(!std::same_as<T, bool> && !std::same_as<T, char>)
    Row& add(T value) {
      return add_formatted(std::to_string(value));
    }

    /// Writes the row. Throws InvalidParameter (nothing written) unless it has one cell per column, and
    /// std::logic_error when called twice.
    void end();

   private:
    friend class CsvWriter;
    explicit Row(CsvWriter& writer) : writer_(&writer) {}
    Row& add_formatted(std::string_view cell);

    CsvWriter* writer_;
    std::string line_;
    std::size_t cells_ = 0;
    bool ended_ = false;
  };

  /// Starts a row: writer.row().add("greedy").add(42).add(0.25).add(true).end();
  [[nodiscard]] Row row() { return Row(*this); }

  const std::vector<std::string>& columns() const noexcept { return columns_; }
  /// Rows written so far (the header not counted).
  std::size_t rows_written() const noexcept { return rows_; }

 private:
  std::ostream& out_;
  std::vector<std::string> columns_;
  std::size_t rows_ = 0;
};

}  // namespace peg3d::results
