#include "agent/server/subscription_book.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace kapfix::agent {
namespace {

using Action = SubscriptionBook::Action;

std::string Subscribe(const std::string& topic) { return "\x01" + topic; }
std::string Unsubscribe(const std::string& topic) { return std::string(1, '\0') + topic; }

TEST(SubscriptionBookTest, SubscriptionsBeyondThePeersBoundAreRefused) {
  SubscriptionBook book({.max_topics_per_peer = 2, .max_topic_bytes = 16, .max_peers = 8},
                        [](const std::string&) { return true; });
  EXPECT_EQ(book.Receive("a", Subscribe("telemetry")).action, Action::kSubscribe);
  EXPECT_EQ(book.Receive("a", Subscribe("video")).action, Action::kSubscribe);
  const SubscriptionBook::Decision third = book.Receive("a", Subscribe("log"));
  EXPECT_EQ(third.action, Action::kIgnore);
  EXPECT_EQ(third.refusal, "more than 2 subscriptions from one peer");
  EXPECT_EQ(book.Receive("b", Subscribe("log")).action, Action::kSubscribe);  // per peer
  EXPECT_EQ(book.TopicsOf("a"), 2U);
}

TEST(SubscriptionBookTest, AnUnsubscriptionFreesItsSlotAndOnlyAdmittedOnesAreApplied) {
  SubscriptionBook book({.max_topics_per_peer = 1, .max_topic_bytes = 16, .max_peers = 8},
                        [](const std::string&) { return true; });
  EXPECT_EQ(book.Receive("a", Subscribe("video")).action, Action::kSubscribe);
  EXPECT_EQ(book.Receive("a", Unsubscribe("log")).action, Action::kIgnore);  // never admitted
  EXPECT_EQ(book.Receive("a", Unsubscribe("video")).action, Action::kUnsubscribe);
  EXPECT_EQ(book.Receive("a", Subscribe("log")).action, Action::kSubscribe);
}

TEST(SubscriptionBookTest, ALongSubscriptionIsRefusedNamingItsLength) {
  SubscriptionBook book({.max_topics_per_peer = 4, .max_topic_bytes = 8, .max_peers = 8},
                        [](const std::string&) { return true; });
  const SubscriptionBook::Decision decision = book.Receive("a", Subscribe("telemetry"));
  EXPECT_EQ(decision.action, Action::kIgnore);
  EXPECT_EQ(decision.refusal, "a subscription of 9 bytes (at most 8)");
}

TEST(SubscriptionBookTest, AFullBookForgetsPeersThatAreGoneButNotConnectedOnes) {
  std::set<std::string> connected = {"a", "b", "c"};
  SubscriptionBook book({.max_topics_per_peer = 4, .max_topic_bytes = 16, .max_peers = 2},
                        [&](const std::string& peer) { return connected.contains(peer); });
  EXPECT_EQ(book.Receive("a", Subscribe("x")).action, Action::kSubscribe);
  EXPECT_EQ(book.Receive("b", Subscribe("x")).action, Action::kSubscribe);
  EXPECT_EQ(book.Receive("c", Subscribe("x")).action, Action::kIgnore);
  connected.erase("a");
  EXPECT_EQ(book.Receive("c", Subscribe("x")).action, Action::kSubscribe);
  EXPECT_EQ(book.TopicsOf("a"), 0U);
  EXPECT_EQ(book.counters().forgotten, 1U);
}

}  // namespace
}  // namespace kapfix::agent
