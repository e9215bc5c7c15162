#include "link/curve_key_pair.hpp"

#include <zmq.h>

#include <array>
#include <cstdint>
#include <stdexcept>

namespace kapfix::link {
namespace {

constexpr std::size_t kZ85KeyChars = 40;
constexpr std::size_t kKeyBytes = 32;

}  // namespace

CurveKeyPair GenerateCurveKeyPair() {
  std::array<char, kZ85KeyChars + 1> public_key{};
  std::array<char, kZ85KeyChars + 1> secret_key{};
  if (zmq_curve_keypair(public_key.data(), secret_key.data()) != 0) {
    throw std::runtime_error(std::string("cannot make a CurveZMQ key pair: ") +
                             zmq_strerror(zmq_errno()) + " (is libzmq built with CURVE support?)");
  }
  return {std::string(public_key.data(), kZ85KeyChars),
          std::string(secret_key.data(), kZ85KeyChars)};
}

bool IsCurveKey(std::string_view z85) {
  if (z85.size() != kZ85KeyChars) return false;
  const std::string text(z85);  // zmq_z85_decode wants a terminated string
  std::array<std::uint8_t, kKeyBytes> bytes{};
  return zmq_z85_decode(bytes.data(), text.c_str()) != nullptr;
}

std::optional<std::string> CurvePublicKeyOf(std::string_view secret_key) {
  if (!IsCurveKey(secret_key)) return std::nullopt;
  const std::string secret(secret_key);
  std::array<char, kZ85KeyChars + 1> public_key{};
  if (zmq_curve_public(public_key.data(), secret.c_str()) != 0) return std::nullopt;
  return std::string(public_key.data(), kZ85KeyChars);
}

bool IsValidKeyPair(const CurveKeyPair& pair, std::string* error) {
  auto fail = [error](const char* message) {
    if (error) *error = message;
    return false;
  };
  if (!IsCurveKey(pair.public_key)) return fail("the public key is not 40 Z85 characters");
  if (!IsCurveKey(pair.secret_key)) return fail("the secret key is not 40 Z85 characters");
  if (CurvePublicKeyOf(pair.secret_key) != pair.public_key) {
    return fail("the public key does not belong to the secret key");
  }
  return true;
}

}  // namespace kapfix::link
