#pragma once

#include <vector>

namespace kapfix {

// Descriptive statistics for benchmark and experiment reports (SPEC §2.10). Every function
// throws std::invalid_argument on empty input; the order statistics (Median, Percentile)
// also reject NaN, which has no place in a sorted order.

double Mean(const std::vector<double>& values);

// Sample standard deviation, sqrt(Σ(x − mean)² / (n − 1)): the thesis's stabilisation figure
// (standard deviation of a tracked point's position, Tables 6.1–6.9). The thesis does not say
// which divisor MINITAB/Excel used; n − 1 is their default, so the figures compare. Needs at
// least two values (one value has no sample spread).
double StandardDeviation(const std::vector<double>& values);

// Middle value; the mean of the two middle values for an even count.
double Median(std::vector<double> values);

// p in [0, 100], linear interpolation between closest ranks: the value at rank
// p / 100 · (n − 1) of the sorted values (NumPy's default, Excel's PERCENTILE.INC).
double Percentile(std::vector<double> values, double p);

// sqrt(Σx² / n): the size of a residual or displacement around zero rather than its mean.
double RootMeanSquare(const std::vector<double>& values);

}  // namespace kapfix
