#include "link/session_recorder.hpp"

#include <array>
#include <limits>
#include <stdexcept>

namespace kapfix::link {
namespace {

template <typename T>
void PutLittleEndian(std::ofstream& out, T value) {
  std::array<char, sizeof(T)> bytes{};
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    bytes[i] = static_cast<char>((static_cast<std::uint64_t>(value) >> (8 * i)) & 0xFFU);
  }
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

void PutBlock(std::ofstream& out, std::string_view block) {
  if (block.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw std::runtime_error("message too large to record");
  }
  PutLittleEndian(out, static_cast<std::uint32_t>(block.size()));
  out.write(block.data(), static_cast<std::streamsize>(block.size()));
}

}  // namespace

SessionRecorder::SessionRecorder(const std::string& path)
    : path_(path), out_(path, std::ios::binary | std::ios::trunc) {
  if (!out_) throw std::runtime_error("cannot create '" + path + "'");
  out_.write(kSessionMagic.data(), static_cast<std::streamsize>(kSessionMagic.size()));
}

void SessionRecorder::Write(std::string_view topic, std::string_view payload,
                            std::int64_t receive_time_us) {
  PutLittleEndian(out_, static_cast<std::uint64_t>(receive_time_us));
  PutBlock(out_, topic);
  PutBlock(out_, payload);
  if (!out_) throw std::runtime_error("cannot write to '" + path_ + "'");
  ++messages_;
}

void SessionRecorder::Flush() {
  out_.flush();
  if (!out_) throw std::runtime_error("cannot write to '" + path_ + "'");
}

}  // namespace kapfix::link
