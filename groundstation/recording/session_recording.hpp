#pragma once

// Records what the views are shown — telemetry, video, reports, photos, log lines, and the
// operator's commands with the agent's replies — in the session file format
// (link/session_recorder.hpp), bytes as they came, so a replay goes through the same
// decoder as the live link.

#include <QObject>
#include <QString>
#include <memory>

#include "groundstation/client/agent_client.hpp"

namespace kapfix::link {
class SessionRecorder;
}

namespace kapfix::station {

class SessionRecording final : public QObject {
  Q_OBJECT

 public:
  explicit SessionRecording(AgentClient& client, QObject* parent = nullptr);
  ~SessionRecording() override;

  // Starts writing to `path` (created or truncated). False with `error` set when it cannot.
  bool start(const QString& path, QString* error = nullptr);
  // Flushes and closes; idempotent.
  void stop();

  bool recording() const { return recorder_ != nullptr; }
  const QString& path() const { return path_; }
  std::uint64_t messages() const;

 signals:
  void recordingChanged(bool recording);
  // A write failed (disk full): the recording stopped.
  void failed(const QString& reason);

 private:
  void write(const QString& topic, const QByteArray& payload, qint64 receive_time_us);

  std::unique_ptr<kapfix::link::SessionRecorder> recorder_;
  QString path_;
};

}  // namespace kapfix::station
