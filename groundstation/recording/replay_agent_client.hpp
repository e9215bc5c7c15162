#pragma once

// A recorded session played back as if an agent sent it: messages come out of
// deliverMessage() at their recorded pace (times a speed factor), so every panel shows the
// replay exactly as it showed the live link. There is no agent behind it: commands are
// refused with that reason.

#include <QTimer>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>

#include "groundstation/client/agent_client.hpp"
#include "link/session_reader.hpp"

namespace kapfix::station {

class ReplayAgentClient final : public AgentClient {
  Q_OBJECT

 public:
  // [ns] a monotonic clock: playback's pace. A steady clock by default; a test moves its own.
  using Clock = std::function<std::int64_t()>;

  explicit ReplayAgentClient(QObject* parent = nullptr);
  explicit ReplayAgentClient(Clock clock, QObject* parent = nullptr);
  ~ReplayAgentClient() override;

  // Opens a recording and stands at its start (paused). False with `error` when the file
  // cannot be read or is not a recording.
  bool open(const QString& path, QString* error = nullptr);
  void close();

  void play();
  void pause();
  bool playing() const { return timer_.isActive(); }
  void setSpeed(double speed);  // [1] 1 = as recorded
  double speed() const { return speed_; }
  // Delivers everything left at once (the end of the recording, without waiting).
  void playToEnd();
  // Delivers what is due by the clock now (the playback timer calls it every tick).
  void advance();

  // [s] recorded time from the first message to the position reached.
  double positionS() const;
  bool atEnd() const { return !next_.has_value(); }
  std::uint64_t delivered() const { return delivered_; }

  void sendCommand(kapfix::v1::Command command, ReplyCallback done = {}) override;
  LinkState linkState() const override { return state_; }

 signals:
  void finished();
  void positionChanged(double seconds);

 private:
  void deliverUntil(std::int64_t time_us);
  std::int64_t clockUs() const;  // [µs, recorded clock] where playback stands now

  std::unique_ptr<kapfix::link::SessionReader> reader_;
  std::optional<kapfix::link::RecordedMessage> next_;
  std::int64_t first_us_ = 0;     // [µs, recorded clock] first message
  std::int64_t position_us_ = 0;  // [µs, recorded clock] where playback stood at started_ns_
  std::int64_t last_us_ = 0;      // [µs, recorded clock] the last message delivered
  Clock clock_;
  std::int64_t started_ns_ = 0;  // [ns, clock_] when position_us_ was taken, while playing
  double speed_ = 1.0;
  std::uint64_t delivered_ = 0;
  LinkState state_;
  QTimer timer_;
};

}  // namespace kapfix::station
