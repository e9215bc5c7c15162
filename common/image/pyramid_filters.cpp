#include "common/image/pyramid_filters.hpp"

#include <algorithm>
#include <cstdint>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "common/image/target_clones.hpp"

namespace kapfix {
namespace {

constexpr int kMid = 128;  // [grey levels] the band-pass's zero

// out[i] = a0[i] + 4·a1[i] + 6·a2[i] + 4·a3[i] + a4[i]: at most 16 · 255, 16 bits.
KAPFIX_KERNEL void VerticalSums(const std::uint8_t* a0, const std::uint8_t* a1,
                                const std::uint8_t* a2, const std::uint8_t* a3,
                                const std::uint8_t* a4, int n, std::uint16_t* out) {
  for (int i = 0; i < n; ++i) {
    out[i] = static_cast<std::uint16_t>(a0[i] + a4[i] + 4 * (a1[i] + a3[i]) + 6 * a2[i]);
  }
}

// out[x] = (Σ [1 4 6 4 1] · c[2x − 2 … 2x + 2] + 128) / 256: the horizontal pass with the
// decimation and pyrDown's rounding. c[−2] … c[2·n + 1] must be readable.
KAPFIX_KERNEL void ReduceRow(const std::uint16_t* c, int n, std::uint8_t* out) {
  for (int x = 0; x < n; ++x) {
    const std::uint16_t* p = c + static_cast<std::ptrdiff_t>(2) * x;
    const unsigned sum = p[-2] + p[2] + 4U * (p[-1] + p[1]) + 6U * p[0] + 128U;
    out[x] = static_cast<std::uint8_t>(sum >> 8);
  }
}

// out[x] = src[x] − (Σ [1 4 6 4 1] · c[x − 2 … x + 2] + 128) / 256 + 128, saturated.
KAPFIX_KERNEL void BandPassRow(const std::uint16_t* c, const std::uint8_t* src, int n,
                               std::uint8_t* out) {
  for (int x = 0; x < n; ++x) {
    const std::uint16_t* p = c + x;
    const int blur = static_cast<int>((p[-2] + p[2] + 4U * (p[-1] + p[1]) + 6U * p[0] + 128U) >> 8);
    out[x] = static_cast<std::uint8_t>(std::clamp(src[x] - blur + kMid, 0, 255));
  }
}

int Reflect101(int i, int n) {
  if (i < 0) return -i;
  if (i >= n) return 2 * n - 2 - i;
  return i;
}

int Replicate(int i, int n) { return std::clamp(i, 0, n - 1); }

}  // namespace

void PyrDown(const cv::Mat& src, cv::Mat& dst) {
  if (src.type() != CV_8UC1 || src.cols < 3 || src.rows < 3) {
    cv::pyrDown(src, dst);
    return;
  }
  const int w = src.cols;
  const int h = src.rows;
  dst.create((h + 1) / 2, (w + 1) / 2, CV_8UC1);
  // Column sums with two reflected columns each side: the horizontal kernel's reach (the last
  // output reads c[w] for an even width, c[w + 1] for an odd one).
  thread_local std::vector<std::uint16_t> sums;
  sums.resize(static_cast<std::size_t>(w) + 4);
  std::uint16_t* c = sums.data() + 2;
  for (int y = 0; y < dst.rows; ++y) {
    const auto row = [&](int k) { return src.ptr<std::uint8_t>(Reflect101(2 * y + k, h)); };
    VerticalSums(row(-2), row(-1), row(0), row(1), row(2), w, c);
    c[-1] = c[1];
    c[-2] = c[2];
    c[w] = c[w - 2];
    c[w + 1] = c[w - 3];
    ReduceRow(c, dst.cols, dst.ptr<std::uint8_t>(y));
  }
}

void BandPass(const cv::Mat& src, cv::Mat& dst) {
  if (src.type() != CV_8UC1 || src.cols < 3 || src.rows < 3) {
    cv::Mat blurred;
    cv::GaussianBlur(src, blurred, cv::Size(5, 5), 0.0, 0.0,
                     cv::BORDER_REPLICATE | cv::BORDER_ISOLATED);
    const double mid = src.depth() == CV_8U ? kMid : 32768.0;
    cv::addWeighted(src, 1.0, blurred, -1.0, mid, dst);
    return;
  }
  const int w = src.cols;
  const int h = src.rows;
  dst.create(h, w, CV_8UC1);
  thread_local std::vector<std::uint16_t> sums;
  sums.resize(static_cast<std::size_t>(w) + 4);
  std::uint16_t* c = sums.data() + 2;
  for (int y = 0; y < h; ++y) {
    const auto row = [&](int k) { return src.ptr<std::uint8_t>(Replicate(y + k, h)); };
    VerticalSums(row(-2), row(-1), row(0), row(1), row(2), w, c);
    c[-1] = c[0];
    c[-2] = c[0];
    c[w] = c[w - 1];
    c[w + 1] = c[w - 1];
    BandPassRow(c, src.ptr<std::uint8_t>(y), w, dst.ptr<std::uint8_t>(y));
  }
}

}  // namespace kapfix
