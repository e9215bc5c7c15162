#include "common/matching/reference_patch.hpp"

#include <algorithm>
#include <stdexcept>

#include "common/matching/ssd_kernel.hpp"

namespace kapfix {

ReferencePatch::ReferencePatch(const cv::Mat& reference, SampleSet samples)
    : image_(reference), samples_(std::move(samples)) {
  if (reference.type() != CV_8UC1 && reference.type() != CV_16UC1 && reference.type() != CV_8UC3) {
    throw std::invalid_argument("ReferencePatch: expected a CV_8UC1, CV_16UC1 or CV_8UC3 plane");
  }
  if (samples_.empty()) throw std::invalid_argument("ReferencePatch: no sampled pixels");
  const cv::Rect frame(0, 0, reference.cols, reference.rows);
  if ((samples_.bounds() & frame) != samples_.bounds()) {
    throw std::invalid_argument("ReferencePatch: sampled pixels lie outside the reference frame");
  }
  const std::vector<cv::Point> points = samples_.Points();
  if (reference.type() == CV_8UC1) {
    values8_.reserve(points.size());
    for (const cv::Point& p : points) values8_.push_back(reference.at<std::uint8_t>(p));
  } else if (reference.type() == CV_8UC3) {
    values8_.reserve(points.size() * 3);
    for (const cv::Point& p : points) {
      const cv::Vec3b& bgr = reference.at<cv::Vec3b>(p);
      values8_.insert(values8_.end(), {bgr[0], bgr[1], bgr[2]});
    }
  } else {
    values16_.reserve(points.size());
    for (const cv::Point& p : points) values16_.push_back(reference.at<std::uint16_t>(p));
  }
  offsets_step_ = reference.step1();
  const auto channels = static_cast<std::size_t>(reference.channels());
  for (const SampleSpan& span : samples_.spans()) {
    span_offsets_.push_back(static_cast<std::int32_t>(span.y * offsets_step_ + span.x * channels));
    span_lengths_.push_back(static_cast<std::int32_t>(span.length * channels));
  }
  single_offsets_.reserve(samples_.singles().size() * channels);
  for (const cv::Point& p : samples_.singles()) {
    for (std::size_t c = 0; c < channels; ++c) {
      single_offsets_.push_back(
          static_cast<std::int32_t>(p.y * offsets_step_ + p.x * channels + c));
    }
  }
}

bool ReferencePatch::CanShift(cv::Size frame, cv::Point shift) const {
  const cv::Rect moved = samples_.bounds() + shift;
  return moved.x >= 0 && moved.y >= 0 && moved.br().x <= frame.width &&
         moved.br().y <= frame.height;
}

ReferencePatch::ShiftInterval ReferencePatch::ShiftRangeX(cv::Size frame, int range) const {
  const cv::Rect b = samples_.bounds();
  return {std::max(-range, -b.x), std::min(range, frame.width - b.br().x)};
}

ReferencePatch::ShiftInterval ReferencePatch::ShiftRangeY(cv::Size frame, int range) const {
  const cv::Rect b = samples_.bounds();
  return {std::max(-range, -b.y), std::min(range, frame.height - b.br().y)};
}

template <typename T>
std::int64_t ReferencePatch::DistanceImpl(const cv::Mat& current, cv::Point shift) const {
  const std::vector<T>& values = [this]() -> const std::vector<T>& {
    if constexpr (sizeof(T) == 1) {
      return values8_;
    } else {
      return values16_;
    }
  }();
  const std::size_t step = current.step1();
  const T* base = current.ptr<T>(shift.y) + shift.x;
  const T* value = values.data();
  std::int64_t sum = 0;
  if (step == offsets_step_) {
    sum = SsdRows(value, base, span_offsets_.data(), span_lengths_.data(),
                  static_cast<int>(span_offsets_.size()));
    value += samples_.size() - single_offsets_.size();
  } else {
    for (const SampleSpan& span : samples_.spans()) {
      sum += SsdRun(value, current.ptr<T>(span.y + shift.y) + span.x + shift.x, span.length);
      value += span.length;
    }
  }
  const auto singles = static_cast<int>(single_offsets_.size());
  if (singles == 0) return sum;
  if (step == offsets_step_) return sum + SsdGather(value, base, single_offsets_.data(), singles);
  // A current plane laid out differently from the reference (an ROI, say): slow path.
  for (const cv::Point& p : samples_.singles()) {
    const std::int64_t d = static_cast<std::int64_t>(*value++) - base[p.y * step + p.x];
    sum += d * d;
  }
  return sum;
}

std::int64_t ReferencePatch::DistanceBgr(const cv::Mat& current, cv::Point shift) const {
  constexpr int kChannels = 3;
  const std::uint8_t* value = values8_.data();
  std::int64_t sum = 0;
  if (current.step1() != offsets_step_) {
    // A current plane laid out differently from the reference (an ROI, say): slow path.
    for (const cv::Point& p : samples_.Points()) {
      const cv::Vec3b& c = current.at<cv::Vec3b>(p + shift);
      for (int k = 0; k < kChannels; ++k) {
        const std::int64_t d = static_cast<std::int64_t>(*value++) - c[k];
        sum += d * d;
      }
    }
    return sum;
  }
  const std::uint8_t* base =
      current.ptr<std::uint8_t>(shift.y) + static_cast<std::ptrdiff_t>(shift.x) * kChannels;
  sum = SsdRows(value, base, span_offsets_.data(), span_lengths_.data(),
                static_cast<int>(span_offsets_.size()));
  value += values8_.size() - single_offsets_.size();
  // SsdGather's 8-bit partial sums hold 132 000 elements; a random sampling of a large patch
  // has three per single, so the singles go in chunks below that.
  constexpr int kChunk = 1 << 16;
  const auto singles = static_cast<int>(single_offsets_.size());
  for (int first = 0; first < singles; first += kChunk) {
    const int n = std::min(kChunk, singles - first);
    sum += SsdGather(value + first, base, single_offsets_.data() + first, n);
  }
  return sum;
}

const std::any& ReferencePatch::Derived(const std::string& key,
                                        const std::function<std::any()>& make) const {
  std::lock_guard lock(derived_->mutex);
  for (const auto& [k, value] : derived_->entries) {
    if (k == key) return value;
  }
  derived_->entries.emplace_back(key, make());
  return derived_->entries.back().second;
}

std::int64_t ReferencePatch::Distance(const cv::Mat& current, cv::Point shift) const {
  CV_DbgAssert(current.type() == type() && CanShift(current.size(), shift));
  if (type() == CV_8UC1) return DistanceImpl<std::uint8_t>(current, shift);
  if (type() == CV_16UC1) return DistanceImpl<std::uint16_t>(current, shift);
  return DistanceBgr(current, shift);
}

}  // namespace kapfix
