#include "agent/resume/boot_id.hpp"

#include <gtest/gtest.h>

#include <set>

namespace kapfix::agent {
namespace {

TEST(BootIdTest, EachDrawIsANewNonZeroId) {
  std::set<std::uint64_t> ids;
  for (int i = 0; i < 100; ++i) {
    const std::uint64_t id = DrawBootId();
    EXPECT_NE(id, 0u);
    ids.insert(id);
  }
  EXPECT_EQ(ids.size(), 100u);
}

}  // namespace
}  // namespace kapfix::agent
