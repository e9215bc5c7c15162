#include "link/legacy_session_reader.hpp"

#include <array>
#include <cstdint>
#include <stdexcept>

#include "kapfix/v1/envelope_codec.hpp"

namespace kapfix::link {
namespace {

template <typename T>
bool GetLittleEndian(std::ifstream& in, T& value) {
  std::array<unsigned char, sizeof(T)> bytes{};
  if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()))) {
    return false;
  }
  std::uint64_t result = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i) result |= std::uint64_t{bytes[i]} << (8 * i);
  value = static_cast<T>(result);
  return true;
}

// A length larger than any link message means a corrupted file: refuse it rather than
// allocate gigabytes.
bool GetBlock(std::ifstream& in, std::string& block) {
  std::uint32_t size = 0;
  if (!GetLittleEndian(in, size) || size > kapfix::v1::kMaxMessageBytes) return false;
  block.resize(size);
  return static_cast<bool>(in.read(block.data(), static_cast<std::streamsize>(size)));
}

}  // namespace

LegacySessionReader::LegacySessionReader(const std::string& path)
    : path_(path), in_(path, std::ios::binary) {
  if (!in_) throw std::runtime_error("cannot open '" + path + "'");
  std::string magic(kLegacySessionMagic.size(), '\0');
  if (!in_.read(magic.data(), static_cast<std::streamsize>(magic.size())) ||
      magic != kLegacySessionMagic) {
    throw std::runtime_error("'" + path + "' is not a KFXREC01 session recording");
  }
}

std::optional<RecordedMessage> LegacySessionReader::Next() {
  const std::streamoff offset = in_.tellg();
  RecordedMessage message;
  std::uint64_t time = 0;
  if (!GetLittleEndian(in_, time)) {
    if (!in_.eof() || in_.gcount() != 0) {
      error_ =
          "'" + path_ + "' (KFXREC01) ends inside the message at byte " + std::to_string(offset);
    }
    return std::nullopt;
  }
  message.receive_time_us = static_cast<std::int64_t>(time);
  if (!GetBlock(in_, message.topic) || !GetBlock(in_, message.payload)) {
    error_ = "'" + path_ + "' (KFXREC01) ends inside the message at byte " +
             std::to_string(offset) + " or holds a corrupted length there";
    return std::nullopt;
  }
  return message;
}

}  // namespace kapfix::link
