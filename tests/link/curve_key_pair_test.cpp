#include "link/curve_key_pair.hpp"

#include <gtest/gtest.h>

namespace kapfix::link {
namespace {

TEST(CurveKeyPairTest, GeneratedPairIsValid) {
  const CurveKeyPair pair = GenerateCurveKeyPair();
  std::string error;
  EXPECT_TRUE(IsValidKeyPair(pair, &error)) << error;
  EXPECT_EQ(pair.public_key.size(), 40U);
}

TEST(CurveKeyPairTest, TwoGeneratedPairsDiffer) {
  EXPECT_NE(GenerateCurveKeyPair().secret_key, GenerateCurveKeyPair().secret_key);
}

TEST(CurveKeyPairTest, PublicKeyIsDerivedFromTheSecretKey) {
  const CurveKeyPair pair = GenerateCurveKeyPair();
  EXPECT_EQ(CurvePublicKeyOf(pair.secret_key), pair.public_key);
}

TEST(CurveKeyPairTest, WrongLengthOrCharactersAreNotKeys) {
  const std::string key = GenerateCurveKeyPair().public_key;
  EXPECT_TRUE(IsCurveKey(key));
  EXPECT_FALSE(IsCurveKey(key.substr(1)));
  EXPECT_FALSE(IsCurveKey(key + "A"));
  EXPECT_FALSE(IsCurveKey(std::string(40, ' ')));  // space is not a Z85 character
  EXPECT_FALSE(IsCurveKey(std::string(40, '"')));
  EXPECT_FALSE(CurvePublicKeyOf("not a key").has_value());
}

TEST(CurveKeyPairTest, HalvesOfDifferentPairsAreRefused) {
  CurveKeyPair mixed = GenerateCurveKeyPair();
  mixed.public_key = GenerateCurveKeyPair().public_key;
  std::string error;
  EXPECT_FALSE(IsValidKeyPair(mixed, &error));
  EXPECT_EQ(error, "the public key does not belong to the secret key");
  // The message never carries the secret itself.
  EXPECT_EQ(error.find(mixed.secret_key), std::string::npos);
}

}  // namespace
}  // namespace kapfix::link
