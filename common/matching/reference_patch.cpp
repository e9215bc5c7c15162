#include "common/matching/reference_patch.hpp"

#include <algorithm>
#include <stdexcept>

#include "common/matching/ssd_kernel.hpp"

namespace kapfix {

ReferencePatch::ReferencePatch(const cv::Mat& reference, SampleSet samples)
    : image_(reference), samples_(std::move(samples)) {
  if (reference.type() != CV_8UC1 && reference.type() != CV_16UC1) {
    throw std::invalid_argument("ReferencePatch: expected a CV_8UC1 or CV_16UC1 plane");
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
  } else {
    values16_.reserve(points.size());
    for (const cv::Point& p : points) values16_.push_back(reference.at<std::uint16_t>(p));
  }
  offsets_step_ = reference.step1();
  for (const SampleSpan& span : samples_.spans()) {
    span_offsets_.push_back(static_cast<std::int32_t>(span.y * offsets_step_ + span.x));
    span_lengths_.push_back(span.length);
  }
  single_offsets_.reserve(samples_.singles().size());
  for (const cv::Point& p : samples_.singles()) {
    single_offsets_.push_back(static_cast<std::int32_t>(p.y * offsets_step_ + p.x));
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
  return type() == CV_8UC1 ? DistanceImpl<std::uint8_t>(current, shift)
                           : DistanceImpl<std::uint16_t>(current, shift);
}

}  // namespace kapfix
