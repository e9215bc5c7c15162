#include "agent/server/subscription_book.hpp"

#include <utility>

namespace kapfix::agent {

bool SubscriptionBookOptions::IsValid(std::string* error) const {
  const auto fail = [&](const char* why) {
    if (error != nullptr) *error = why;
    return false;
  };
  if (max_topics_per_peer == 0) return fail("max_topics_per_peer must be at least 1");
  if (max_topic_bytes == 0) return fail("max_topic_bytes must be at least 1");
  if (max_peers == 0) return fail("max_peers must be at least 1");
  return true;
}

SubscriptionBook::SubscriptionBook(SubscriptionBookOptions options,
                                   std::function<bool(const std::string&)> connected)
    : options_(options), connected_(std::move(connected)) {}

bool SubscriptionBook::ForgetGone() {
  bool any = false;
  for (auto it = topics_.begin(); it != topics_.end();) {
    if (connected_ && connected_(it->first)) {
      ++it;
      continue;
    }
    it = topics_.erase(it);
    ++counters_.forgotten;
    any = true;
  }
  return any;
}

SubscriptionBook::Decision SubscriptionBook::Receive(const std::string& peer,
                                                     std::string_view message) {
  Decision decision;
  // libzmq's unsubscriptions for a closed connection come from no peer; an empty message is
  // not a subscription.
  if (peer.empty() || message.empty()) return decision;
  const auto kind = static_cast<unsigned char>(message.front());
  const std::string_view topic = message.substr(1);
  if (kind != 0 && kind != 1) {
    // XPUB passes other messages from subscribers through as well; they mean nothing here.
    return decision;
  }
  auto found = topics_.find(peer);
  if (kind == 0) {
    if (found == topics_.end()) return decision;
    const auto topic_found = found->second.find(topic);
    if (topic_found == found->second.end()) return decision;  // never admitted
    found->second.erase(topic_found);
    decision.action = Action::kUnsubscribe;
    decision.topic = topic;
    return decision;
  }
  if (topic.size() > options_.max_topic_bytes) {
    ++counters_.refused;
    decision.refusal = "a subscription of " + std::to_string(topic.size()) + " bytes (at most " +
                       std::to_string(options_.max_topic_bytes) + ")";
    return decision;
  }
  if (found == topics_.end()) {
    if (topics_.size() >= options_.max_peers && !ForgetGone()) {
      ++counters_.refused;
      decision.refusal =
          "subscriptions from more than " + std::to_string(options_.max_peers) + " connected peers";
      return decision;
    }
    found = topics_.try_emplace(peer).first;
  }
  std::set<std::string, std::less<>>& mine = found->second;
  if (mine.contains(topic)) return decision;  // a repeat: libzmq already holds it
  if (mine.size() >= options_.max_topics_per_peer) {
    ++counters_.refused;
    decision.refusal = "more than " + std::to_string(options_.max_topics_per_peer) +
                       " subscriptions from one peer";
    return decision;
  }
  mine.emplace(topic);
  ++counters_.admitted;
  decision.action = Action::kSubscribe;
  decision.topic = topic;
  return decision;
}

std::size_t SubscriptionBook::TopicsOf(const std::string& peer) const {
  const auto found = topics_.find(peer);
  return found == topics_.end() ? 0 : found->second.size();
}

}  // namespace kapfix::agent
