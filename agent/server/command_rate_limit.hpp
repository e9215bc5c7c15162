#pragma once

// How many commands the agent takes, per station and from all stations together (issue 15:
// a command flood from 10 stations must not slow the control loop). Two token buckets decide
// each command: the station's own and one shared by all; a command takes a token from both or
// is refused, before it is decoded, validated or executed, with a reason naming the rate.
//
// The station is whatever CommandServer can tell apart and a peer cannot multiply by
// reconnecting: its CurveZMQ key (the name the authorised-keys file gives it), else its IP
// address, else (no address: ipc://, inproc://) its connection. The shared bucket bounds the
// sum whatever the keying: many addresses or keys still get no more than its rate.
//
// Pure and not thread-safe: one owner (the command server's thread); time is passed in, so
// tests need no clock.

#include <chrono>
#include <cstddef>
#include <string>
#include <string_view>
#include <unordered_map>

namespace kapfix::agent {

struct CommandRateLimitOptions {
  // [commands/s] sustained per station; a station's own use (a click, a slider, a state
  // request a second) is a few a second.
  double station_per_s = 20;
  double station_burst = 40;  // [commands] taken at once by a station that sent none for a while
  // [commands/s] sustained from all stations together: what the command thread may cost the
  // control loop's core at most.
  double all_per_s = 100;
  double all_burst = 200;  // [commands]
  // [count] stations whose buckets are kept; beyond it, full buckets (those that changed
  // nothing) are forgotten, and when none is full the newcomer shares one overflow bucket.
  std::size_t max_stations = 4096;

  // Rates 0.1…100000/s and bursts 1…1000000 (a burst below 1 could never admit a command),
  // the shared ones at least the station's (else one station alone would meet the shared
  // limit first), max_stations at least 1.
  bool IsValid(std::string* error) const;
};

class CommandRateLimit {
 public:
  using Clock = std::chrono::steady_clock;

  struct Decision {
    bool allowed = false;
    std::string reason;  // why not, naming the rate ("rate limited: at most 20 commands/s ...")
    // When the bucket that refused has a token again (the shared one: not before the
    // station's own token interval).
    Clock::time_point retry_at;
  };

  explicit CommandRateLimit(CommandRateLimitOptions options);

  // One command from `station` at `now`: a token from its bucket and from the shared one, or a
  // refusal that takes none.
  Decision Take(std::string_view station, Clock::time_point now);

  std::size_t stations_tracked() const { return stations_.size(); }

 private:
  struct Bucket {
    double tokens = 0;  // [commands]
    Clock::time_point updated;
  };

  Bucket& StationBucket(std::string_view station, Clock::time_point now);

  const CommandRateLimitOptions options_;
  Bucket all_;
  Bucket overflow_;
  std::unordered_map<std::string, Bucket> stations_;
};

}  // namespace kapfix::agent
