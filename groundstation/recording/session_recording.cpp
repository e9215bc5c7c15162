#include "groundstation/recording/session_recording.hpp"

#include <stdexcept>

#include "link/session_recorder.hpp"

namespace kapfix::station {

SessionRecording::SessionRecording(AgentClient& client, QObject* parent) : QObject(parent) {
  connect(&client, &AgentClient::messageReceived, this, &SessionRecording::write);
}

SessionRecording::~SessionRecording() { stop(); }

bool SessionRecording::start(const QString& path, QString* error) {
  stop();
  try {
    recorder_ = std::make_unique<kapfix::link::SessionRecorder>(path.toStdString());
  } catch (const std::runtime_error& failure) {
    if (error != nullptr) *error = QString::fromUtf8(failure.what());
    return false;
  }
  path_ = path;
  emit recordingChanged(true);
  return true;
}

void SessionRecording::stop() {
  if (!recorder_) return;
  try {
    recorder_->Flush();
  } catch (const std::runtime_error& failure) {
    emit failed(QString::fromUtf8(failure.what()));
  }
  recorder_.reset();
  emit recordingChanged(false);
}

std::uint64_t SessionRecording::messages() const { return recorder_ ? recorder_->messages() : 0; }

void SessionRecording::write(const QString& topic, const QByteArray& payload,
                             qint64 receive_time_us) {
  if (!recorder_) return;
  try {
    const QByteArray topic_bytes = topic.toUtf8();
    recorder_->Write(
        std::string_view(topic_bytes.constData(), static_cast<std::size_t>(topic_bytes.size())),
        std::string_view(payload.constData(), static_cast<std::size_t>(payload.size())),
        receive_time_us);
  } catch (const std::runtime_error& failure) {
    recorder_.reset();
    emit failed(QString::fromUtf8(failure.what()));
    emit recordingChanged(false);
  }
}

}  // namespace kapfix::station
