#include "common/control/controller_factory.hpp"

#include <gtest/gtest.h>

namespace kapfix {
namespace {

TEST(ControllerFactoryTest, MakesEachNamedController) {
  for (const std::string& name : ControllerNames()) {
    std::string error;
    const auto controller = MakeController(name, {}, {0.1, 0.1}, {}, &error);
    ASSERT_NE(controller, nullptr) << error;
    EXPECT_EQ(controller->name(), name);
  }
  EXPECT_EQ(ControllerNames().back(), "predictive");
}

TEST(ControllerFactoryTest, UnknownNameGivesAReason) {
  std::string error;
  EXPECT_EQ(MakeController("bang-bang", {}, {0.1, 0.1}, {}, &error), nullptr);
  EXPECT_NE(error.find("bang-bang"), std::string::npos);
}

}  // namespace
}  // namespace kapfix
