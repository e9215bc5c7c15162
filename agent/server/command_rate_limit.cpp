#include "agent/server/command_rate_limit.hpp"

#include <algorithm>
#include <cstdio>
#include <iterator>

namespace kapfix::agent {
namespace {

constexpr double kMinRate = 0.1;      // [commands/s]
constexpr double kMaxRate = 100'000;  // [commands/s]
constexpr double kMaxBurst = 1'000'000;

// "20", "0.5": a rate as a person writes it.
std::string Number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// Refills `bucket` for the time since it was last looked at.
void Refill(double& tokens, CommandRateLimit::Clock::time_point& updated, double per_s,
            double burst, CommandRateLimit::Clock::time_point now) {
  const double elapsed_s = std::chrono::duration<double>(now - updated).count();
  if (elapsed_s > 0) {
    tokens = std::min(burst, tokens + elapsed_s * per_s);
    updated = now;
  }
}

CommandRateLimit::Clock::time_point WhenOneToken(double tokens, double per_s,
                                                 CommandRateLimit::Clock::time_point now) {
  const double wait_s = std::max(0.0, (1.0 - tokens) / per_s);
  // Rounded up: at retry_at the bucket has its token, never a hair less.
  return now + std::chrono::ceil<CommandRateLimit::Clock::duration>(
                   std::chrono::duration<double>(wait_s));
}

}  // namespace

bool CommandRateLimitOptions::IsValid(std::string* error) const {
  const auto fail = [error](const std::string& why) {
    if (error != nullptr) *error = why;
    return false;
  };
  const auto rate_ok = [](double rate) { return rate >= kMinRate && rate <= kMaxRate; };
  const auto burst_ok = [](double burst) { return burst >= 1 && burst <= kMaxBurst; };
  if (!rate_ok(station_per_s)) {
    return fail("station_per_s must be 0.1…100000 commands/s, got " + Number(station_per_s));
  }
  if (!burst_ok(station_burst)) {
    return fail("station_burst must be 1…1000000 commands, got " + Number(station_burst));
  }
  if (!rate_ok(all_per_s) || all_per_s < station_per_s) {
    return fail("all_per_s must be 0.1…100000 commands/s and at least station_per_s, got " +
                Number(all_per_s));
  }
  if (!burst_ok(all_burst) || all_burst < station_burst) {
    return fail("all_burst must be 1…1000000 commands and at least station_burst, got " +
                Number(all_burst));
  }
  if (max_stations == 0) return fail("max_stations must be at least 1");
  return true;
}

CommandRateLimit::CommandRateLimit(CommandRateLimitOptions options)
    : options_(options), all_{options_.all_burst, {}}, overflow_{options_.station_burst, {}} {}

CommandRateLimit::Bucket& CommandRateLimit::StationBucket(std::string_view station,
                                                          Clock::time_point now) {
  const auto found = stations_.find(std::string(station));
  if (found != stations_.end()) return found->second;
  if (stations_.size() >= options_.max_stations) {
    // A full bucket is the same as none: forgetting it loses nothing a station could gain by.
    for (auto it = stations_.begin(); it != stations_.end();) {
      Bucket& bucket = it->second;
      Refill(bucket.tokens, bucket.updated, options_.station_per_s, options_.station_burst, now);
      it = bucket.tokens >= options_.station_burst ? stations_.erase(it) : std::next(it);
    }
    if (stations_.size() >= options_.max_stations) return overflow_;
  }
  return stations_.emplace(std::string(station), Bucket{options_.station_burst, now}).first->second;
}

CommandRateLimit::Decision CommandRateLimit::Take(std::string_view station, Clock::time_point now) {
  Bucket& own = StationBucket(station, now);
  Refill(own.tokens, own.updated, options_.station_per_s, options_.station_burst, now);
  Refill(all_.tokens, all_.updated, options_.all_per_s, options_.all_burst, now);
  Decision decision;
  if (own.tokens < 1) {
    decision.reason = "rate limited: at most " + Number(options_.station_per_s) +
                      " commands/s per station (a burst of " + Number(options_.station_burst) + ")";
    decision.retry_at = WhenOneToken(own.tokens, options_.station_per_s, now);
    return decision;
  }
  if (all_.tokens < 1) {
    decision.reason = "rate limited: the agent takes at most " + Number(options_.all_per_s) +
                      " commands/s from all stations together";
    // Not before the station's own next token either: the stations that share the bucket
    // would otherwise all come back at its next token, and most be refused again.
    decision.retry_at = std::max(WhenOneToken(all_.tokens, options_.all_per_s, now),
                                 WhenOneToken(0, options_.station_per_s, now));
    return decision;
  }
  own.tokens -= 1;
  all_.tokens -= 1;
  decision.allowed = true;
  decision.retry_at = now;
  return decision;
}

}  // namespace kapfix::agent
