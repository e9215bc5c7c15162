#include "agent/config/config_reader.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace kapfix::agent {
namespace {

using nlohmann::json;

TEST(ConfigReaderTest, AbsentKeyKeepsTheDefault) {
  const json object = json::object();
  ConfigReader reader(object, "camera");
  double fps = 30;
  EXPECT_TRUE(reader.Read("fps", &fps));
  EXPECT_EQ(fps, 30);
}

TEST(ConfigReaderTest, WrongTypeNamesTheFieldAndTheValue) {
  const json object = {{"fps", "fast"}};
  ConfigReader reader(object, "camera");
  double fps = 30;
  EXPECT_FALSE(reader.Read("fps", &fps));
  EXPECT_EQ(reader.error(), "camera.fps: must be a number, got a string \"fast\"");
}

TEST(ConfigReaderTest, FractionIsNotAnInteger) {
  const json object = {{"width", 640.5}};
  ConfigReader reader(object, "camera");
  int width = 0;
  EXPECT_FALSE(reader.Read("width", &width));
}

TEST(ConfigReaderTest, UnknownKeyIsNamedByFinish) {
  const json object = {{"fps", 25}, {"fsp", 30}};
  ConfigReader reader(object, "camera");
  double fps = 0;
  reader.Read("fps", &fps);
  EXPECT_FALSE(reader.Finish());
  EXPECT_NE(reader.error().find("camera.fsp: unknown key"), std::string::npos) << reader.error();
}

TEST(ConfigReaderTest, HexStringIsAnInteger) {
  const json object = {{"i2c_address", "0x41"}};
  ConfigReader reader(object, "servo");
  int address = 0;
  EXPECT_TRUE(reader.ReadInteger("i2c_address", &address));
  EXPECT_EQ(address, 0x41);
}

TEST(ConfigReaderTest, GarbageIntegerStringIsAnError) {
  const json object = {{"i2c_address", "0x4g"}};
  ConfigReader reader(object, "servo");
  int address = 0;
  EXPECT_FALSE(reader.ReadInteger("i2c_address", &address));
}

TEST(ConfigReaderTest, NullClearsAnOptional) {
  const json object = {{"gain_db", nullptr}};
  ConfigReader reader(object, "camera");
  std::optional<double> gain = 3.0;
  EXPECT_TRUE(reader.Read("gain_db", &gain));
  EXPECT_FALSE(gain.has_value());
}

TEST(ConfigReaderTest, NestedErrorsCarryTheFullPath) {
  const json object = {{"pan", {{"max_deg", true}}}};
  ConfigReader reader(object, "servo");
  double max_deg = 0;
  reader.ReadObject("pan", [&](ConfigReader& pan) { return pan.Read("max_deg", &max_deg); });
  EXPECT_EQ(reader.error().rfind("servo.pan.max_deg:", 0), 0u) << reader.error();
}

TEST(ConfigReaderTest, ArrayElementsAreNamedByIndex) {
  const json object = {{"lenses", json::array({json::object(), {{"nmae", "x"}}})}};
  ConfigReader reader(object, "");
  std::string name;
  reader.ReadObjectArray("lenses",
                         [&](ConfigReader& lens, std::size_t) { return lens.Read("name", &name); });
  EXPECT_EQ(reader.error().rfind("lenses[1].nmae: unknown key", 0), 0u) << reader.error();
}

TEST(ConfigReaderTest, NonObjectIsAnError) {
  const json array = json::array();
  ConfigReader reader(array, "");
  EXPECT_FALSE(reader.ok());
}

TEST(ConfigReaderTest, OnlyTheFirstErrorIsKept) {
  const json object = {{"a", "x"}, {"b", "y"}};
  ConfigReader reader(object, "s");
  double a = 0;
  double b = 0;
  reader.Read("a", &a);
  reader.Read("b", &b);
  EXPECT_EQ(reader.error().rfind("s.a:", 0), 0u) << reader.error();
}

}  // namespace
}  // namespace kapfix::agent
