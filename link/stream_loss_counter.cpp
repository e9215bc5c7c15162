#include "link/stream_loss_counter.hpp"

namespace kapfix::link {

std::uint64_t StreamLossCounter::Received(std::string_view topic,
                                          const kapfix::v1::Header& header) {
  auto it = topics_.find(topic);
  if (it == topics_.end()) it = topics_.emplace(std::string(topic), Topic{}).first;
  Topic& entry = it->second;
  std::uint64_t missing = 0;
  // Another boot, or a number not above the last: the agent restarted its numbering.
  if (entry.last != 0 && header.boot_id() == entry.boot_id && header.sequence() > entry.last + 1) {
    missing = header.sequence() - entry.last - 1;
  }
  entry.last = header.sequence();
  entry.boot_id = header.boot_id();
  entry.lost += missing;
  total_ += missing;
  return missing;
}

std::uint64_t StreamLossCounter::Heard(const kapfix::v1::Heartbeat& heartbeat) {
  std::uint64_t missing = 0;
  for (const kapfix::v1::TopicCount& newest : heartbeat.newest_sequence()) {
    const auto it = topics_.find(newest.topic());
    // A topic never received: its messages may all predate the subscription.
    if (it == topics_.end() || it->second.last == 0) continue;
    Topic& entry = it->second;
    // From another boot, or behind: the next message of the topic starts it over.
    if (heartbeat.header().boot_id() != entry.boot_id || newest.count() <= entry.last) continue;
    const std::uint64_t tail = newest.count() - entry.last;
    entry.last = newest.count();  // counted once: a later message numbers from here
    entry.lost += tail;
    missing += tail;
  }
  total_ += missing;
  return missing;
}

std::uint64_t StreamLossCounter::Lost(std::string_view topic) const {
  const auto it = topics_.find(topic);
  return it == topics_.end() ? 0 : it->second.lost;
}

void StreamLossCounter::FillLost(kapfix::v1::Heartbeat* heartbeat) const {
  for (const auto& [topic, entry] : topics_) {
    if (entry.lost == 0) continue;
    kapfix::v1::TopicCount* count = heartbeat->add_lost();
    count->set_topic(topic);
    count->set_count(entry.lost);
  }
}

}  // namespace kapfix::link
