#pragma once

// Replay protection across connections (issue 15, item 8). The per-connection SequenceGuard
// lets a captured command be accepted again on a new connection (a new routing id), also
// stamped 1970. This adds, per station (its CURVE key, or one shared id for plain stations):
// - header.send_time_us must lie within ±window of the agent's clock, refused with a reason
//   naming the skew;
// - and after a horizon: nothing stamped at or before it is accepted. The horizon is the
//   agent's start time, or the newest send time accepted in an earlier run if later (an agent
//   whose clock came back behind, e.g. a Raspberry Pi without a real-time clock), persisted
//   in the state folder at most once a second [the commands of the last second before a crash
//   are the exception, when the clock also stepped back];
// - a command (station, send_time_us, sequence) already accepted within the window is a
//   replay. Entries older than the window are forgotten: the window check refuses them.
// A station that restarts (kapfix-ctl: every run) numbers from 1 again; its send times, not
// its sequence numbers, are what is monotonic across connections. Not thread-safe: one owner.

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <set>
#include <string>
#include <string_view>
#include <tuple>
#include <unordered_map>

namespace kapfix::agent {

struct ReplayWindowOptions {
  std::chrono::seconds window{30};  // [s] accepted |send_time_us - agent clock|
  // Where the horizon is kept between runs; empty = not persisted (the horizon is this run's
  // start).
  std::filesystem::path state_file;
  std::size_t max_remembered = 100'000;  // [commands] within the window, all stations

  bool IsValid(std::string* error) const;
};

class ReplayWindow {
 public:
  // `now_us` [µs since epoch]: the agent's clock at start.
  ReplayWindow(ReplayWindowOptions options, std::int64_t now_us);
  ~ReplayWindow();  // persists the newest accepted send time
  ReplayWindow(const ReplayWindow&) = delete;
  ReplayWindow& operator=(const ReplayWindow&) = delete;

  // True and remembered when the command may be executed; false with a one-line reason.
  bool Accept(std::string_view station, std::int64_t send_time_us, std::uint64_t sequence,
              std::int64_t now_us, std::string* error);

  std::int64_t horizon_us() const { return horizon_us_; }

 private:
  void Persist(std::int64_t now_us);

  ReplayWindowOptions options_;
  std::int64_t horizon_us_ = 0;          // [µs since epoch] accepted send times are after it
  std::int64_t newest_accepted_us_ = 0;  // [µs since epoch]
  std::int64_t persisted_at_us_ = 0;     // [µs since epoch] agent clock at the last write
  // (send time, station, sequence) accepted within the window, oldest first.
  std::set<std::tuple<std::int64_t, std::string, std::uint64_t>> accepted_;
};

}  // namespace kapfix::agent
