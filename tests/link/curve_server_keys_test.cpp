// ReadCurveServerKeys (issue 15, item 13): an authorised-keys file that others can write is
// refused, since whoever writes it can authorise a station.
#include "link/curve_server_keys.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "link/curve_key_file.hpp"
#include "link/curve_key_pair.hpp"
#include "tests/support/temp_dir.hpp"

namespace kapfix::link {
namespace {

class CurveServerKeysTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string error;
    ASSERT_TRUE(kapfix::link::WriteSecretKeyFile(secret_, kapfix::link::GenerateCurveKeyPair(),
                                                 "agent", false, &error))
        << error;
    ASSERT_TRUE(kapfix::link::WritePublicKeyFile(
        authorised_, kapfix::link::GenerateCurveKeyPair().public_key, "laptop", false, &error))
        << error;
  }

  kapfix::testing::TempDir temp_;
  std::filesystem::path secret_ = temp_.path() / "agent.key";
  std::filesystem::path authorised_ = temp_.path() / "authorized_keys";
};

TEST_F(CurveServerKeysTest, AuthorisedKeysFileOnlyTheOwnerCanWriteIsRead) {
  std::filesystem::permissions(authorised_, std::filesystem::perms(0644));
  std::string error;
  const auto keys = ReadCurveServerKeys(secret_, authorised_, &error);
  ASSERT_TRUE(keys) << error;
  EXPECT_EQ(keys->authorized_stations.size(), 1U);
}

TEST_F(CurveServerKeysTest, AuthorisedKeysFileWritableByEveryoneIsRefusedNamingTheMode) {
  std::filesystem::permissions(authorised_, std::filesystem::perms(0666));
  std::string error;
  EXPECT_FALSE(ReadCurveServerKeys(secret_, authorised_, &error));
  EXPECT_NE(error.find("writable by group or others (mode 0666)"), std::string::npos) << error;
}

TEST_F(CurveServerKeysTest, AuthorisedKeysFileWritableByTheGroupIsRefused) {
  std::filesystem::permissions(authorised_, std::filesystem::perms(0664));
  EXPECT_FALSE(ReadCurveServerKeys(secret_, authorised_, nullptr));
}

}  // namespace
}  // namespace kapfix::link
