#pragma once

// What each subscriber of the agent's streams has subscribed to (issue 15): the stream socket
// runs in ZMQ_XPUB_MANUAL mode, so every subscription reaches the agent as a message and is
// applied only when this book admits it. A peer can hold at most max_topics_per_peer distinct
// subscriptions of at most max_topic_bytes each; libzmq's trie for it is bounded by their
// product; the publisher ends the connection of a peer whose subscription is refused (libzmq
// holds every subscription it has read for a connection, applied or not, until it closes).
// Pure logic, no sockets: the publisher names each peer (ZeroMQ descriptor and the
// address of its connection) and says which peers are still connected.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <string_view>

namespace kapfix::agent {

struct SubscriptionBookOptions {
  // [count] distinct subscriptions per peer; a station needs one per topic (about a dozen,
  // or one empty prefix for all).
  std::size_t max_topics_per_peer = 32;
  // [bytes] the longest prefix admitted; topics are at most a dozen characters.
  std::size_t max_topic_bytes = 64;
  // [count] peers remembered; beyond it, peers no longer connected are forgotten first.
  std::size_t max_peers = 4096;
  bool IsValid(std::string* error) const;
};

class SubscriptionBook {
 public:
  enum class Action {
    kSubscribe,    // apply it (ZMQ_SUBSCRIBE for the peer the message came from)
    kUnsubscribe,  // apply it (ZMQ_UNSUBSCRIBE)
    kIgnore,       // not a subscription, from no known peer, a repeat, or refused
  };
  struct Decision {
    Action action = Action::kIgnore;
    std::string_view topic;  // into the message given to Receive
    std::string refusal;     // why a subscription was refused; empty otherwise
  };
  struct Counters {
    std::uint64_t admitted = 0;   // [count] subscriptions applied
    std::uint64_t refused = 0;    // [count] over a bound or malformed
    std::uint64_t forgotten = 0;  // [count] peers dropped from the book (gone)
  };

  // `connected(peer)`: whether a peer named earlier is still connected (the publisher checks
  // its descriptor), asked only when the book is full.
  SubscriptionBook(SubscriptionBookOptions options,
                   std::function<bool(const std::string&)> connected);

  // One message a subscriber sent (byte 1 = subscribe, 0 = unsubscribe, then the prefix).
  // `peer` empty: libzmq's own unsubscription for a connection that closed, which it has
  // already applied.
  Decision Receive(const std::string& peer, std::string_view message);

  std::size_t TopicsOf(const std::string& peer) const;
  std::size_t peers() const { return topics_.size(); }
  Counters counters() const { return counters_; }

 private:
  // Forgets peers no longer connected; false when every remembered peer still is.
  bool ForgetGone();

  SubscriptionBookOptions options_;
  std::function<bool(const std::string&)> connected_;
  std::map<std::string, std::set<std::string, std::less<>>, std::less<>> topics_;
  Counters counters_;
};

}  // namespace kapfix::agent
