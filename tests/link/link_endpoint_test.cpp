// ParseLinkEndpoint (issue 15, item 2): exactly one endpoint per option, judged on its literal
// address, one test per trick that got past the loopback-only rule.
#include "link/link_endpoint.hpp"

#include <gtest/gtest.h>

#include <string>

namespace kapfix::link {
namespace {

TEST(LinkEndpointTest, SourceAndBindPairIsRefusedNamingTheSemicolon) {
  std::string error;
  EXPECT_FALSE(ParseLinkEndpoint("tcp://127.0.0.1:0;0.0.0.0:8555", &error));
  EXPECT_NE(error.find("';'"), std::string::npos) << error;
}

TEST(LinkEndpointTest, TwoEndpointsSeparatedByACommaOrSpaceAreRefused) {
  EXPECT_FALSE(ParseLinkEndpoint("tcp://127.0.0.1:5555,tcp://0.0.0.0:5555", nullptr));
  EXPECT_FALSE(ParseLinkEndpoint("tcp://127.0.0.1:5555 tcp://0.0.0.0:5555", nullptr));
}

TEST(LinkEndpointTest, LocalhostIsResolvedTo127001) {
  const auto endpoint = ParseLinkEndpoint("tcp://localhost:5555", nullptr);
  ASSERT_TRUE(endpoint);
  EXPECT_EQ(endpoint->canonical, "tcp://127.0.0.1:5555");
  EXPECT_TRUE(endpoint->loopback);
}

TEST(LinkEndpointTest, HostNameThatStartsLikeLoopbackIsRefused) {
  std::string error;
  EXPECT_FALSE(ParseLinkEndpoint("tcp://127.0.0.1.example.org:5555", &error));
  EXPECT_NE(error.find("127.0.0.1.example.org"), std::string::npos) << error;
}

TEST(LinkEndpointTest, InterfaceNameIsRefused) {
  EXPECT_FALSE(ParseLinkEndpoint("tcp://eth0:5555", nullptr));
  EXPECT_FALSE(ParseLinkEndpoint("tcp://lo:5555", nullptr));
}

TEST(LinkEndpointTest, ShortAndHexadecimalIpv4SpellingsAreRefused) {
  EXPECT_FALSE(ParseLinkEndpoint("tcp://127.1:5555", nullptr));
  EXPECT_FALSE(ParseLinkEndpoint("tcp://0x7f000001:5555", nullptr));
  EXPECT_FALSE(ParseLinkEndpoint("tcp://0177.0.0.1:5555", nullptr));
}

TEST(LinkEndpointTest, AnyLoopbackAddressIsLoopbackAndOthersAreNot) {
  EXPECT_TRUE(ParseLinkEndpoint("tcp://127.0.0.1:5555", nullptr)->loopback);
  EXPECT_TRUE(ParseLinkEndpoint("tcp://127.3.2.1:5555", nullptr)->loopback);
  EXPECT_TRUE(ParseLinkEndpoint("tcp://[::1]:5555", nullptr)->loopback);
  EXPECT_FALSE(ParseLinkEndpoint("tcp://*:5555", nullptr)->loopback);
  EXPECT_FALSE(ParseLinkEndpoint("tcp://0.0.0.0:5555", nullptr)->loopback);
  EXPECT_FALSE(ParseLinkEndpoint("tcp://[::]:5555", nullptr)->loopback);
  EXPECT_FALSE(ParseLinkEndpoint("tcp://192.168.1.2:5555", nullptr)->loopback);
  EXPECT_FALSE(ParseLinkEndpoint("tcp://[::ffff:127.0.0.1]:5555", nullptr)->loopback);
}

TEST(LinkEndpointTest, IpcAndInprocAreLoopback) {
  EXPECT_TRUE(ParseLinkEndpoint("ipc:///run/kapfix/command", nullptr)->loopback);
  EXPECT_TRUE(ParseLinkEndpoint("inproc://command", nullptr)->loopback);
  EXPECT_FALSE(ParseLinkEndpoint("ipc://", nullptr));
}

TEST(LinkEndpointTest, EphemeralPortIsAccepted) {
  EXPECT_EQ(ParseLinkEndpoint("tcp://127.0.0.1:*", nullptr)->canonical, "tcp://127.0.0.1:*");
  EXPECT_FALSE(ParseLinkEndpoint("tcp://127.0.0.1:65536", nullptr));
  EXPECT_FALSE(ParseLinkEndpoint("tcp://127.0.0.1:", nullptr));
}

}  // namespace
}  // namespace kapfix::link
