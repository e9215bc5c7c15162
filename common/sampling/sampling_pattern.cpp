#include "common/sampling/sampling_pattern.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>

namespace kapfix {

bool SamplingOptions::IsValid(std::string* error) const {
  if (kind == SamplingKind::kRandom && !(fraction > 0.0 && fraction <= 1.0)) {
    if (error) *error = "sampling fraction must be in (0, 1], got " + std::to_string(fraction);
    return false;
  }
  return true;
}

bool ParseSamplingOptions(std::string_view text, SamplingOptions* options, std::string* error) {
  SamplingOptions parsed;
  if (text == "all") {
    parsed.kind = SamplingKind::kAll;
  } else if (text == "static") {
    parsed.kind = SamplingKind::kStatic;
  } else if (text == "random") {
    parsed.kind = SamplingKind::kRandom;
  } else if (text.starts_with("random:")) {
    parsed.kind = SamplingKind::kRandom;
    const std::string number(text.substr(7));
    char* end = nullptr;
    parsed.fraction = std::strtod(number.c_str(), &end);
    if (number.empty() || end != number.c_str() + number.size()) {
      if (error) *error = "sampling: '" + number + "' is not a number";
      return false;
    }
  } else {
    if (error) {
      *error = "unknown sampling '" + std::string(text) + "' (all, static, random or random:F)";
    }
    return false;
  }
  if (!parsed.IsValid(error)) return false;
  *options = parsed;
  return true;
}

std::string ToString(const SamplingOptions& options) {
  switch (options.kind) {
    case SamplingKind::kAll:
      return "all";
    case SamplingKind::kStatic:
      return "static";
    case SamplingKind::kRandom:
      return "random:" + std::to_string(options.fraction);
  }
  return "?";
}

std::vector<cv::Point> MakeSamplingPattern(cv::Size patch, const SamplingOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  if (patch.width <= 0 || patch.height <= 0) {
    throw std::invalid_argument("sampling pattern needs a non-empty patch");
  }
  const int area = patch.area();
  std::vector<int> indices;
  switch (options.kind) {
    case SamplingKind::kAll:
      indices.resize(static_cast<std::size_t>(area));
      std::iota(indices.begin(), indices.end(), 0);
      break;
    case SamplingKind::kStatic: {
      for (int i = 0, gap = 10; i < area; i += gap, gap = gap == 1 ? 10 : gap - 1) {
        indices.push_back(i);
      }
      break;
    }
    case SamplingKind::kRandom: {
      const auto count =
          std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(options.fraction * area)));
      std::vector<int> pool(static_cast<std::size_t>(area));
      std::iota(pool.begin(), pool.end(), 0);
      std::mt19937 generator(options.seed);
      for (std::size_t i = 0; i < count; ++i) {
        const auto remaining = static_cast<std::uint32_t>(pool.size() - i);
        const std::size_t pick = i + generator() % remaining;
        std::swap(pool[i], pool[pick]);
      }
      indices.assign(pool.begin(), pool.begin() + static_cast<std::ptrdiff_t>(count));
      std::sort(indices.begin(), indices.end());
      break;
    }
  }
  std::vector<cv::Point> offsets;
  offsets.reserve(indices.size());
  for (const int index : indices) offsets.emplace_back(index % patch.width, index / patch.width);
  return offsets;
}

}  // namespace kapfix
