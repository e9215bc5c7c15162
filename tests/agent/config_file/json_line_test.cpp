#include "agent/config_file/json_line.hpp"

#include <gtest/gtest.h>

namespace kapfix::agent {
namespace {

constexpr const char* kText = R"({
  "camera": {"fps": 30},
  "settings": {
    "camera": {
      "gain_db": 3
    }
  }
})";

TEST(JsonLineTest, FindsANestedKeyAfterItsParents) {
  // "camera" first appears on line 2; settings.camera is the one on line 4.
  EXPECT_EQ(JsonLineOf(kText, "settings.camera.gain_db"), 5);
  EXPECT_EQ(JsonLineOf(kText, "camera.fps"), 2);
}

TEST(JsonLineTest, AKeyThatIsNotThereHasNoLine) {
  EXPECT_EQ(JsonLineOf(kText, "settings.video"), 0);
  EXPECT_EQ(JsonLineOf(kText, ""), 0);
}

TEST(JsonLineTest, AValueEqualToAKeyIsNotTakenForTheKey) {
  EXPECT_EQ(JsonLineOf("{\"a\": \"fps\",\n \"fps\": 1}", "fps"), 2);
}

TEST(JsonLineTest, AnIndexFindsTheArraysKey) {
  EXPECT_EQ(JsonLineOf("{\n\"lenses\": [{}]}", "lenses[0]"), 2);
}

TEST(JsonLineTest, TheFieldOfAReasonIsItsLeadingPath) {
  EXPECT_EQ(FieldOfReason("settings.gains.p = 11: must be in [0.01, 10]"), "settings.gains.p");
  EXPECT_EQ(FieldOfReason("lenses[1]: lens name 'a' is used twice"), "lenses[1]");
  EXPECT_EQ(FieldOfReason("not a settings command"), "");
  EXPECT_EQ(FieldOfReason("invalid JSON: parse error at line 3"), "");
}

}  // namespace
}  // namespace kapfix::agent
