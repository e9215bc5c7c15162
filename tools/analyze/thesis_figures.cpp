#include "tools/analyze/thesis_figures.hpp"

namespace kapfix::analyze {

std::vector<CalibrationSample> ThesisTable41Samples() {
  // Rows: moves −100 … +100; columns D1 … D5 [px], as printed.
  static const double kD[21][5] = {
      {-94, -94, -90, -90, -96}, {-84, -86, -80, -86, -86}, {-74, -76, -76, -76, -78},
      {-66, -64, -64, -64, -62}, {-56, -54, -54, -56, -54}, {-46, -50, -50, -50, -50},
      {-38, -40, -40, -40, -40}, {-28, -30, -32, -30, -32}, {-24, -22, -22, -22, -22},
      {-16, -14, -12, -14, -14}, {-4, -4, -4, -4, -4},      {6, 6, 4, 6, 4},
      {14, 14, 14, 14, 12},      {22, 22, 18, 18, 18},      {28, 30, 28, 26, 26},
      {36, 36, 36, 36, 34},      {44, 46, 44, 44, 44},      {52, 54, 52, 52, 52},
      {58, 62, 62, 58, 56},      {66, 66, 66, 64, 66},      {74, 74, 74, 74, 74}};
  std::vector<CalibrationSample> samples;
  for (int row = 0; row < 21; ++row) {
    for (const double d : kD[row]) samples.push_back({-100.0 + 10.0 * row, d});
  }
  return samples;
}

const std::vector<ThesisSuccessRow>& ThesisTable32() {
  static const std::vector<ThesisSuccessRow> rows = {
      {"Garden", "aero3.jpg", 77, 59},
      {"Flower", "butterfly.jpg", 73, 52},
      {"Door", "building.jpg", 20, 24},
  };
  return rows;
}

const std::vector<ThesisSliceRow>& ThesisTable51() {
  static const std::vector<ThesisSliceRow> rows = {
      {"Flower", "butterfly.jpg", 4, 87, 6, 309}, {"City", "aero1.jpg", 4, 82, 9, 548},
      {"Garden", "aero3.jpg", 1, 138, 6, 344},    {"River", "fruits.jpg", 6, 87, 1, 606},
      {"Door", "building.jpg", 6, 188, 3, 412},   {"Beach", "home.jpg", 6, 75, 9, 562},
      {"Lake", "messi5.jpg", 3, 74, 9, 526},      {"Building", "baboon.jpg", 4, 129, 1, 312},
      {"Street", "leuvenA.jpg", 3, 88, 9, 243},   {"Duck", "graf1.png", 5, 76, 9, 436}};
  return rows;
}

const std::vector<std::string>& ThesisStandInPhotos() {
  static const std::vector<std::string> photos = {
      "aero3.jpg",  "building.jpg", "butterfly.jpg", "aero1.jpg",  "leuvenA.jpg",
      "fruits.jpg", "home.jpg",     "messi5.jpg",    "baboon.jpg", "graf1.png"};
  return photos;
}

}  // namespace kapfix::analyze
