// kapfix-analyze's copies of the thesis's tables, checked against the tables as printed in the
// thesis, typed in here independently (column by column for Table 4.1, where the program keeps
// rows), so that a slip in either copy shows.
#include "tools/analyze/thesis_figures.hpp"

#include <gtest/gtest.h>

#include <array>
#include <map>
#include <string>
#include <vector>

namespace kapfix::analyze {
namespace {

TEST(ThesisFiguresTest, Table41HoldsTheFiveRoundsOfDisplacementsAsPrinted) {
  // Table 4.1's columns D1 … D5 [px], moves −100, −90, …, +100.
  const std::array<std::array<double, 21>, 5> columns = {{
      {-94, -84, -74, -66, -56, -46, -38, -28, -24, -16, -4, 6, 14, 22, 28, 36, 44, 52, 58, 66, 74},
      {-94, -86, -76, -64, -54, -50, -40, -30, -22, -14, -4, 6, 14, 22, 30, 36, 46, 54, 62, 66, 74},
      {-90, -80, -76, -64, -54, -50, -40, -32, -22, -12, -4, 4, 14, 18, 28, 36, 44, 52, 62, 66, 74},
      {-90, -86, -76, -64, -56, -50, -40, -30, -22, -14, -4, 6, 14, 18, 26, 36, 44, 52, 58, 64, 74},
      {-96, -86, -78, -62, -54, -50, -40, -32, -22, -14, -4, 4, 12, 18, 26, 34, 44, 52, 56, 66, 74},
  }};
  std::map<double, std::vector<double>> by_move;
  for (const CalibrationSample& sample : ThesisTable41Samples()) {
    by_move[sample.servo_move].push_back(sample.displacement_px);
  }
  ASSERT_EQ(by_move.size(), 21u);
  for (int row = 0; row < 21; ++row) {
    const double move = -100.0 + 10.0 * row;
    std::vector<double> printed;
    for (const auto& column : columns) printed.push_back(column[static_cast<std::size_t>(row)]);
    EXPECT_EQ(by_move[move], printed) << "move " << move;
  }
  EXPECT_DOUBLE_EQ(kThesisCalibration, 1.11);  // "Median(C1, …, C5) = 1.11"
}

TEST(ThesisFiguresTest, Table32HoldsTheStaticAndRandomSuccessRatesAsPrinted) {
  struct Printed {
    double static_pct;
    double random_pct;
  };
  const std::map<std::string, Printed> printed = {
      {"Garden", {77, 59}}, {"Flower", {73, 52}}, {"Door", {20, 24}}};
  ASSERT_EQ(ThesisTable32().size(), printed.size());
  for (const ThesisSuccessRow& row : ThesisTable32()) {
    ASSERT_EQ(printed.count(row.image), 1u) << row.image;
    EXPECT_EQ(row.static_pct, printed.at(row.image).static_pct) << row.image;
    EXPECT_EQ(row.random_pct, printed.at(row.image).random_pct) << row.image;
  }
}

TEST(ThesisFiguresTest, Table51HoldsTheBestAndWorstSlicesAsPrinted) {
  // Table 5.1's rows: best slice, best DC, worst slice, worst DC per image.
  const std::map<std::string, std::array<int, 4>> printed = {
      {"Flower", {4, 87, 6, 309}}, {"City", {4, 82, 9, 548}},      {"Garden", {1, 138, 6, 344}},
      {"River", {6, 87, 1, 606}},  {"Door", {6, 188, 3, 412}},     {"Beach", {6, 75, 9, 562}},
      {"Lake", {3, 74, 9, 526}},   {"Building", {4, 129, 1, 312}}, {"Street", {3, 88, 9, 243}},
      {"Duck", {5, 76, 9, 436}}};
  ASSERT_EQ(ThesisTable51().size(), printed.size());
  for (const ThesisSliceRow& row : ThesisTable51()) {
    ASSERT_EQ(printed.count(row.image), 1u) << row.image;
    const std::array<int, 4> ours = {row.best_slice, row.best_dc, row.worst_slice, row.worst_dc};
    EXPECT_EQ(ours, printed.at(row.image)) << row.image;
  }
}

}  // namespace
}  // namespace kapfix::analyze
