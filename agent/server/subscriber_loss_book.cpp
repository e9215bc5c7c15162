#include "agent/server/subscriber_loss_book.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace kapfix::agent {

bool SubscriberLossBookOptions::IsValid(std::string* error) const {
  const auto fail = [error](const char* why) {
    if (error != nullptr) *error = why;
    return false;
  };
  if (max_stations == 0) return fail("subscriber loss book: max_stations must be at least 1");
  if (max_topics == 0) return fail("subscriber loss book: max_topics must be at least 1");
  if (max_topic_bytes == 0) return fail("subscriber loss book: max_topic_bytes must be at least 1");
  if (notice_period.count() < 0) return fail("subscriber loss book: notice_period is negative");
  return true;
}

std::uint64_t StationLosses::total() const {
  std::uint64_t sum = 0;
  for (const auto& [topic, count] : by_topic) sum += count;
  return sum;
}

SubscriberLossBook::SubscriberLossBook(SubscriberLossBookOptions options) : options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument(error);
}

std::string SubscriberLossBook::Report(const std::string& station,
                                       const kapfix::v1::Heartbeat& heartbeat,
                                       Clock::time_point now) {
  const std::lock_guard lock(mutex_);
  auto it = std::find_if(entries_.begin(), entries_.end(),
                         [&](const Entry& entry) { return entry.losses.station == station; });
  if (it == entries_.end()) {
    if (entries_.size() >= options_.max_stations) entries_.pop_back();
    Entry fresh;
    fresh.losses.station = station;
    fresh.window_start = now;
    entries_.push_front(std::move(fresh));
  } else {
    entries_.splice(entries_.begin(), entries_, it);
  }
  Entry& entry = entries_.front();
  for (const kapfix::v1::TopicCount& count : heartbeat.lost()) {
    if (count.topic().size() > options_.max_topic_bytes) continue;
    const bool known = entry.losses.by_topic.contains(count.topic());
    if (!known && entry.losses.by_topic.size() >= options_.max_topics) continue;
    std::uint64_t& kept = entry.losses.by_topic[count.topic()];
    // Lower: the station counts afresh; what it counted before is no longer in its reports.
    if (count.count() < kept) entry.at_notice[count.topic()] = 0;
    kept = count.count();
  }
  if (entry.noticed && now - entry.window_start < options_.notice_period) return {};
  std::ostringstream grown;
  std::uint64_t grown_total = 0;
  for (const auto& [topic, count] : entry.losses.by_topic) {
    const std::uint64_t before = entry.at_notice[topic];
    if (count <= before) continue;
    grown << (grown_total == 0 ? "" : " and ") << (count - before) << " " << topic;
    grown_total += count - before;
  }
  if (grown_total == 0) {
    // Nothing lost for a whole period: the next notice counts from here, and is given at once.
    if (now - entry.window_start >= options_.notice_period) {
      entry.at_notice = entry.losses.by_topic;
      entry.window_start = now;
      entry.noticed = false;
    }
    return {};
  }
  const auto seconds = std::chrono::duration_cast<std::chrono::seconds>(now - entry.window_start);
  std::ostringstream notice;
  notice << "station " << station << " lost " << grown.str() << " messages in the last "
         << std::max<std::int64_t>(seconds.count(), 1)
         << " s: it reads too slowly or its link is saturated";
  entry.at_notice = entry.losses.by_topic;
  entry.window_start = now;
  entry.noticed = true;
  return notice.str();
}

std::vector<StationLosses> SubscriberLossBook::Stations() const {
  const std::lock_guard lock(mutex_);
  std::vector<StationLosses> stations;
  stations.reserve(entries_.size());
  for (const Entry& entry : entries_) stations.push_back(entry.losses);
  return stations;
}

std::uint64_t SubscriberLossBook::TotalLost(const std::string& station) const {
  const std::lock_guard lock(mutex_);
  for (const Entry& entry : entries_) {
    if (entry.losses.station == station) return entry.losses.total();
  }
  return 0;
}

}  // namespace kapfix::agent
