#pragma once

// What each station says it lost of the agent's streams (issue 15, per-subscriber isolation).
// libzmq's XPUB drops a whole message for a subscriber whose queue is full without saying
// which; each station counts its own losses (link::StreamLossCounter) and reports them, per
// topic and since it subscribed, in every heartbeat it sends to the command server
// (Heartbeat.lost). This book keeps the latest report of each station, bounded in stations
// (the least recently heard is forgotten first) and in topics per station, and says when a
// station's losses grew, at most once per notice_period per station:
// "station <id> lost N telemetry messages in the last 10 s: it reads too slowly or its link is
// saturated". Thread-safe: the command server's thread reports, anyone reads.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <list>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "kapfix/v1/heartbeat.pb.h"

namespace kapfix::agent {

struct SubscriberLossBookOptions {
  std::size_t max_stations = 64;           // [count] stations remembered at once
  std::size_t max_topics = 32;             // [count] topics kept per station; more are ignored
  std::size_t max_topic_bytes = 64;        // [bytes] longer topic names are ignored
  std::chrono::seconds notice_period{10};  // at most one notice per station per period

  bool IsValid(std::string* error) const;
};

struct StationLosses {
  std::string station;                            // as SubscriberLossBook::Report was told
  std::map<std::string, std::uint64_t> by_topic;  // [count] lost, as last reported
  std::uint64_t total() const;
};

class SubscriberLossBook {
 public:
  using Clock = std::chrono::steady_clock;

  // Throws std::invalid_argument for invalid options.
  explicit SubscriberLossBook(SubscriberLossBookOptions options = {});

  // `station` reported `heartbeat.lost()` at `now`. Returns the notice to log when its losses
  // grew and no notice was given for it within notice_period, naming what it lost since the
  // last notice (or since the start of the last period without losses); empty otherwise. A count
  // lower than the last one is a station that started counting afresh (a restarted station): its
  // growth counts from 0.
  std::string Report(const std::string& station, const kapfix::v1::Heartbeat& heartbeat,
                     Clock::time_point now);

  // Every station remembered, most recently heard first.
  std::vector<StationLosses> Stations() const;
  // [count] what `station` reported lost over every topic; 0 for an unknown station.
  std::uint64_t TotalLost(const std::string& station) const;

 private:
  struct Entry {
    StationLosses losses;
    std::map<std::string, std::uint64_t> at_notice;  // counts when the last notice was given
    Clock::time_point window_start;                  // when the counts at_notice were taken
    bool noticed = false;  // a notice was given at window_start: the next waits a period
  };

  const SubscriberLossBookOptions options_;
  mutable std::mutex mutex_;
  std::list<Entry> entries_;  // most recently heard first
};

}  // namespace kapfix::agent
