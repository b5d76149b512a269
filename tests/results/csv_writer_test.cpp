#include "results/csv_writer.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/validation.hpp"
#include "support/numbers.hpp"

namespace peg3d::results {
namespace {

using testing::kInf;
using testing::kNaN;

TEST(ResultsCsvWriter, WritesHeaderAndRows) {
  std::ostringstream out;
  CsvWriter csv(out, {"algorithm", "seed", "capture_rate", "captured"});
  csv.row().add("facl").add(7).add(0.25).add(true).end();
  csv.row().add(std::string("greedy")).add(std::uint64_t{8}).add(1.0).add(false).end();
  EXPECT_EQ(out.str(),
            "algorithm,seed,capture_rate,captured\n"
            "facl,7,0.25,true\n"
            "greedy,8,1,false\n");
  EXPECT_EQ(csv.rows_written(), 2u);
}

TEST(ResultsCsvWriter, DoublesAreShortestRoundTrip) {
  EXPECT_EQ(format_csv_double(0.1), "0.1");
  EXPECT_EQ(format_csv_double(1.0 / 3.0), "0.3333333333333333");
  EXPECT_EQ(format_csv_double(1e-12), "1e-12");
  EXPECT_EQ(format_csv_double(3.0), "3");
  EXPECT_EQ(format_csv_double(-2.5), "-2.5");
  EXPECT_EQ(format_csv_double(0.1 + 0.2), "0.30000000000000004");
}

TEST(ResultsCsvWriter, DoublesReadBackExactly) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-300, 300);
  for (int i = 0; i < 2000; ++i) {
    const double x = std::ldexp(mantissa(rng), exponent(rng));
    const std::string text = format_csv_double(x);
    EXPECT_EQ(std::strtod(text.c_str(), nullptr), x) << text;
  }
}

TEST(ResultsCsvWriter, NonFiniteDoublesHaveFixedSpelling) {
  EXPECT_EQ(format_csv_double(kNaN), "nan");
  EXPECT_EQ(format_csv_double(-kNaN), "nan");
  EXPECT_EQ(format_csv_double(kInf), "inf");
  EXPECT_EQ(format_csv_double(-kInf), "-inf");
  EXPECT_EQ(format_csv_double(-0.0), "-0");
}

TEST(ResultsCsvWriter, FieldsAreQuotedOnlyWhenNeeded) {
  EXPECT_EQ(quote_csv_field("plain text"), "plain text");
  EXPECT_EQ(quote_csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(quote_csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(quote_csv_field("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(quote_csv_field("cr\r"), "\"cr\r\"");
  EXPECT_EQ(quote_csv_field(""), "");
}

TEST(ResultsCsvWriter, HeaderAndCellsAreQuoted) {
  std::ostringstream out;
  CsvWriter csv(out, {"name", "note, free text"});
  csv.row().add("x").add("a \"quoted\", text").end();
  EXPECT_EQ(out.str(), "name,\"note, free text\"\nx,\"a \"\"quoted\"\", text\"\n");
}

TEST(ResultsCsvWriter, IntegersPrintInFull) {
  std::ostringstream out;
  CsvWriter csv(out, {"a", "b", "c", "d"});
  csv.row()
      .add(-3)
      .add(std::numeric_limits<std::int64_t>::min())
      .add(std::numeric_limits<std::uint64_t>::max())
      .add(std::size_t{0})
      .end();
  EXPECT_EQ(out.str(), "a,b,c,d\n-3,-9223372036854775808,18446744073709551615,0\n");
}

TEST(ResultsCsvWriter, NanCellPrintsNan) {
  std::ostringstream out;
  CsvWriter csv(out, {"capture_time"});
  csv.row().add(kNaN).end();
  EXPECT_EQ(out.str(), "capture_time\nnan\n");
}

TEST(ResultsCsvWriter, LoneEmptyFieldIsQuoted) {
  std::ostringstream out;
  CsvWriter csv(out, {"note"});
  csv.row().add("").end();
  EXPECT_EQ(out.str(), "note\n\"\"\n");
}

TEST(ResultsCsvWriter, WrongCellCountThrowsAndWritesNothing) {
  std::ostringstream out;
  CsvWriter csv(out, {"a", "b"});
  EXPECT_THROW(csv.row().add(1).end(), InvalidParameter);
  EXPECT_THROW(csv.row().add(1).add(2).add(3).end(), InvalidParameter);
  EXPECT_EQ(out.str(), "a,b\n");
  EXPECT_EQ(csv.rows_written(), 0u);
}

TEST(ResultsCsvWriter, RowWithoutEndWritesNothing) {
  std::ostringstream out;
  CsvWriter csv(out, {"a"});
  { auto row = csv.row().add(1); }
  EXPECT_EQ(out.str(), "a\n");
}

TEST(ResultsCsvWriter, EndTwiceIsALogicError) {
  std::ostringstream out;
  CsvWriter csv(out, {"a"});
  auto row = csv.row();
  row.add(1).end();
  EXPECT_THROW(row.end(), std::logic_error);
  EXPECT_EQ(out.str(), "a\n1\n");
}

TEST(ResultsCsvWriter, RejectsEmptyOrDuplicateColumns) {
  std::ostringstream out;
  EXPECT_THROW(CsvWriter(out, {}), InvalidParameter);
  EXPECT_THROW(CsvWriter(out, {"a", "b", "a"}), InvalidParameter);
}

}  // namespace
}  // namespace peg3d::results
