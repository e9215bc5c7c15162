#include "link/curve_key_file.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>

#include "tests/support/temp_dir.hpp"

namespace kapfix::link {
namespace {

using kapfix::testing::TempDir;
using ::testing::HasSubstr;

mode_t ModeOf(const std::filesystem::path& path) {
  struct stat info {};
  EXPECT_EQ(::stat(path.c_str(), &info), 0) << path;
  return info.st_mode & 0777U;
}

void WriteText(const std::filesystem::path& path, const std::string& text, mode_t mode) {
  std::ofstream(path) << text;
  ASSERT_EQ(::chmod(path.c_str(), mode), 0);
}

TEST(CurveKeyFileTest, SecretKeyFileIsWrittenWithMode0600WhateverTheUmask) {
  TempDir dir;
  const mode_t old = ::umask(0);  // the widest umask: nothing masked
  std::string error;
  const bool written =
      WriteSecretKeyFile(dir.path() / "a.key", GenerateCurveKeyPair(), "a", false, &error);
  ::umask(old);
  ASSERT_TRUE(written) << error;
  EXPECT_EQ(ModeOf(dir.path() / "a.key"), 0600U);
}

TEST(CurveKeyFileTest, SecretKeyFileReadsBackTheSamePair) {
  TempDir dir;
  const CurveKeyPair pair = GenerateCurveKeyPair();
  std::string error;
  ASSERT_TRUE(WriteSecretKeyFile(dir.path() / "a.key", pair, "a", false, &error)) << error;
  EXPECT_EQ(ReadSecretKeyFile(dir.path() / "a.key", &error), pair) << error;
}

TEST(CurveKeyFileTest, ExistingKeyFileIsNotReplacedWithoutOverwrite) {
  TempDir dir;
  const CurveKeyPair first = GenerateCurveKeyPair();
  std::string error;
  ASSERT_TRUE(WriteSecretKeyFile(dir.path() / "a.key", first, "a", false, &error));
  EXPECT_FALSE(
      WriteSecretKeyFile(dir.path() / "a.key", GenerateCurveKeyPair(), "a", false, &error));
  EXPECT_THAT(error, HasSubstr("already exists"));
  EXPECT_EQ(ReadSecretKeyFile(dir.path() / "a.key", &error), first);
}

TEST(CurveKeyFileTest, OverwriteReplacesTheKey) {
  TempDir dir;
  std::string error;
  ASSERT_TRUE(WriteSecretKeyFile(dir.path() / "a.key", GenerateCurveKeyPair(), "a", false, &error));
  const CurveKeyPair second = GenerateCurveKeyPair();
  ASSERT_TRUE(WriteSecretKeyFile(dir.path() / "a.key", second, "a", true, &error)) << error;
  EXPECT_EQ(ReadSecretKeyFile(dir.path() / "a.key", &error), second);
}

TEST(CurveKeyFileTest, SecretKeyFileReadableByOthersIsRefused) {
  TempDir dir;
  std::string error;
  ASSERT_TRUE(WriteSecretKeyFile(dir.path() / "a.key", GenerateCurveKeyPair(), "a", false, &error));
  ASSERT_EQ(::chmod((dir.path() / "a.key").c_str(), 0644), 0);
  EXPECT_FALSE(ReadSecretKeyFile(dir.path() / "a.key", &error).has_value());
  EXPECT_THAT(error, HasSubstr("mode 0644"));
  EXPECT_THAT(error, HasSubstr("chmod 600"));
}

TEST(CurveKeyFileTest, MissingSecretKeyFileIsNamedInTheError) {
  TempDir dir;
  std::string error;
  EXPECT_FALSE(ReadSecretKeyFile(dir.path() / "none.key", &error).has_value());
  EXPECT_THAT(error, HasSubstr("none.key"));
}

TEST(CurveKeyFileTest, GarbageSecretKeyFileIsRefusedWithItsLine) {
  TempDir dir;
  WriteText(dir.path() / "g.key", "# comment\npublic-key = x\nsomething else\n", 0600);
  std::string error;
  EXPECT_FALSE(ReadSecretKeyFile(dir.path() / "g.key", &error).has_value());
  EXPECT_THAT(error, HasSubstr("line 3"));
}

TEST(CurveKeyFileTest, SecretKeyFileWithMismatchedHalvesIsRefused) {
  TempDir dir;
  WriteText(dir.path() / "m.key",
            "public-key = " + GenerateCurveKeyPair().public_key +
                "\nsecret-key = " + GenerateCurveKeyPair().secret_key + "\n",
            0600);
  std::string error;
  EXPECT_FALSE(ReadSecretKeyFile(dir.path() / "m.key", &error).has_value());
  EXPECT_THAT(error, HasSubstr("does not belong"));
}

TEST(CurveKeyFileTest, PublicKeyFileReadsBackItsKey) {
  TempDir dir;
  const CurveKeyPair pair = GenerateCurveKeyPair();
  std::string error;
  ASSERT_TRUE(WritePublicKeyFile(dir.path() / "a.pub", pair.public_key, "a", false, &error));
  EXPECT_EQ(ReadPublicKeyFile(dir.path() / "a.pub", &error), pair.public_key) << error;
}

TEST(CurveKeyFileTest, AuthorisedKeysSkipCommentsAndKeepNames) {
  TempDir dir;
  const std::string a = GenerateCurveKeyPair().public_key;
  const std::string b = GenerateCurveKeyPair().public_key;
  WriteText(dir.path() / "authorized", "# stations\n\n" + a + " laptop one\n  " + b + "\n", 0644);
  std::string error;
  const auto entries = ReadPublicKeyLines(dir.path() / "authorized", &error);
  ASSERT_TRUE(entries.has_value()) << error;
  EXPECT_EQ(*entries, (std::vector<PublicKeyEntry>{{a, "laptop one"}, {b, ""}}));
}

TEST(CurveKeyFileTest, AuthorisedKeysLineThatIsNotAKeyIsRefusedWithItsLine) {
  TempDir dir;
  WriteText(dir.path() / "authorized", GenerateCurveKeyPair().public_key + "\nnonsense\n", 0644);
  std::string error;
  EXPECT_FALSE(ReadPublicKeyLines(dir.path() / "authorized", &error).has_value());
  EXPECT_THAT(error, HasSubstr("line 2"));
}

TEST(CurveKeyFileTest, PublicKeyFileWithTwoKeysIsRefused) {
  TempDir dir;
  WriteText(dir.path() / "two.pub",
            GenerateCurveKeyPair().public_key + "\n" + GenerateCurveKeyPair().public_key + "\n",
            0644);
  std::string error;
  EXPECT_FALSE(ReadPublicKeyFile(dir.path() / "two.pub", &error).has_value());
  EXPECT_THAT(error, HasSubstr("holds 2 keys"));
}

}  // namespace
}  // namespace kapfix::link
