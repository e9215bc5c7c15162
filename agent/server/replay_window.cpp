#include "agent/server/replay_window.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <string>

#include "common/io/atomic_file.hpp"

namespace kapfix::agent {
namespace {

constexpr std::int64_t kMicrosPerSecond = 1'000'000;
constexpr std::int64_t kPersistPeriodUs = kMicrosPerSecond;  // [µs] at most one write a second

std::string Seconds(std::int64_t us) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", static_cast<double>(us) / 1e6);
  return text;
}

}  // namespace

bool ReplayWindowOptions::IsValid(std::string* error) const {
  if (window.count() < 1 || window.count() > 3600) {
    if (error) *error = "replay window: " + std::to_string(window.count()) + " s, must be 1…3600 s";
    return false;
  }
  if (max_remembered == 0) {
    if (error) *error = "replay window: max_remembered must be at least 1";
    return false;
  }
  return true;
}

ReplayWindow::ReplayWindow(ReplayWindowOptions options, std::int64_t now_us)
    : options_(std::move(options)), horizon_us_(now_us) {
  if (options_.state_file.empty()) return;
  std::ifstream in(options_.state_file);
  std::int64_t stored = 0;
  if (in >> stored && stored > horizon_us_) horizon_us_ = stored;
  newest_accepted_us_ = horizon_us_;
}

ReplayWindow::~ReplayWindow() {
  if (!options_.state_file.empty() && newest_accepted_us_ > horizon_us_) Persist(0);
}

bool ReplayWindow::Accept(std::string_view station, std::int64_t send_time_us,
                          std::uint64_t sequence, std::int64_t now_us, std::string* error) {
  const std::int64_t window_us = options_.window.count() * kMicrosPerSecond;
  const std::int64_t skew_us = send_time_us - now_us;
  if (skew_us > window_us || skew_us < -window_us) {
    if (error) {
      *error = "command stamped " + Seconds(std::abs(skew_us)) + " s " +
               (skew_us > 0 ? "ahead of" : "behind") + " the agent's clock (accepted: ±" +
               std::to_string(options_.window.count()) +
               " s): set the station's or the agent's clock";
    }
    return false;
  }
  if (send_time_us <= horizon_us_) {
    if (error) {
      *error = "command stamped " + Seconds(horizon_us_ - send_time_us) +
               " s before the agent's replay horizon (its start or an earlier run's last "
               "command): a replay, or sent before the agent started";
    }
    return false;
  }
  auto entry = std::make_tuple(send_time_us, std::string(station), sequence);
  if (accepted_.contains(entry)) {
    if (error) {
      *error = "replayed command: sequence " + std::to_string(sequence) + " sent at " +
               std::to_string(send_time_us) + " µs was already accepted";
    }
    return false;
  }
  // Forget what the window refuses anyway, and the oldest beyond the bound.
  while (!accepted_.empty() && (std::get<0>(*accepted_.begin()) < now_us - window_us ||
                                accepted_.size() >= options_.max_remembered)) {
    // Past the bound, the oldest's send time becomes the horizon: nothing older is accepted.
    if (std::get<0>(*accepted_.begin()) >= now_us - window_us) {
      horizon_us_ = std::get<0>(*accepted_.begin());
    }
    accepted_.erase(accepted_.begin());
  }
  accepted_.insert(std::move(entry));
  if (send_time_us > newest_accepted_us_) newest_accepted_us_ = send_time_us;
  if (!options_.state_file.empty() && now_us - persisted_at_us_ >= kPersistPeriodUs) {
    Persist(now_us);
  }
  return true;
}

void ReplayWindow::Persist(std::int64_t now_us) {
  persisted_at_us_ = now_us;
  try {
    std::error_code ignored;
    std::filesystem::create_directories(options_.state_file.parent_path(), ignored);
    WriteFileAtomically(options_.state_file, std::to_string(newest_accepted_us_) + "\n");
  } catch (const std::exception& failure) {
    spdlog::warn("replay horizon not saved: {}", failure.what());
  }
}

}  // namespace kapfix::agent
