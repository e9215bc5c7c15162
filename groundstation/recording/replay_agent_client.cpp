#include "groundstation/recording/replay_agent_client.hpp"

#include <QFileInfo>
#include <QMetaObject>
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <stdexcept>

#include "link/session_reader.hpp"

namespace kapfix::station {
namespace {

constexpr int kTickMs = 10;  // [ms] playback granularity

}  // namespace

ReplayAgentClient::ReplayAgentClient(QObject* parent)
    : ReplayAgentClient(
          [] {
            return std::chrono::duration_cast<std::chrono::nanoseconds>(
                       std::chrono::steady_clock::now().time_since_epoch())
                .count();
          },
          parent) {}

ReplayAgentClient::ReplayAgentClient(Clock clock, QObject* parent)
    : AgentClient(parent), clock_(std::move(clock)) {
  timer_.setInterval(kTickMs);
  connect(&timer_, &QTimer::timeout, this, &ReplayAgentClient::advance);
  state_.replay = true;
}

ReplayAgentClient::~ReplayAgentClient() = default;

bool ReplayAgentClient::open(const QString& path, QString* error) {
  close();
  try {
    reader_ = std::make_unique<kapfix::link::SessionReader>(path.toStdString());
  } catch (const std::runtime_error& failure) {
    if (error != nullptr) *error = QString::fromUtf8(failure.what());
    return false;
  }
  next_ = reader_->Next();
  first_us_ = next_ ? next_->receive_time_us : 0;
  position_us_ = first_us_;
  last_us_ = first_us_;
  state_ = LinkState{};
  state_.replay = true;
  state_.up = true;
  state_.source = QFileInfo(path).fileName();
  emit linkChanged(state_);
  return true;
}

void ReplayAgentClient::close() {
  timer_.stop();
  reader_.reset();
  next_.reset();
  delivered_ = 0;
}

void ReplayAgentClient::play() {
  if (!reader_ || atEnd()) return;
  started_ns_ = clock_();
  timer_.start();
}

void ReplayAgentClient::pause() {
  if (!timer_.isActive()) return;
  position_us_ = clockUs();
  timer_.stop();
}

void ReplayAgentClient::setSpeed(double speed) {
  if (speed <= 0) return;
  position_us_ = clockUs();
  started_ns_ = clock_();
  speed_ = speed;
}

void ReplayAgentClient::playToEnd() {
  timer_.stop();
  deliverUntil(INT64_MAX);
  position_us_ = std::max(position_us_, last_us_);
}

double ReplayAgentClient::positionS() const {
  return static_cast<double>(clockUs() - first_us_) / 1e6;
}

std::int64_t ReplayAgentClient::clockUs() const {
  if (!timer_.isActive()) return position_us_;
  return position_us_ +
         static_cast<std::int64_t>(static_cast<double>(clock_() - started_ns_) / 1e3 * speed_);
}

void ReplayAgentClient::advance() {
  if (playing()) deliverUntil(clockUs());
}

void ReplayAgentClient::deliverUntil(std::int64_t time_us) {
  while (next_ && next_->receive_time_us <= time_us) {
    const kapfix::link::RecordedMessage message = std::move(*next_);
    next_ = reader_->Next();
    if (deliverMessage(message.topic, message.payload, message.receive_time_us)) ++delivered_;
    last_us_ = message.receive_time_us;
  }
  emit positionChanged(positionS());
  if (!next_ && reader_) {
    position_us_ = last_us_;
    timer_.stop();
    state_.up = false;
    emit linkChanged(state_);
    emit finished();
    reader_.reset();
  }
}

void ReplayAgentClient::sendCommand(kapfix::v1::Command /*command*/, ReplyCallback done) {
  CommandOutcome outcome;
  outcome.reason = tr("replaying a recording: there is no agent to command");
  QMetaObject::invokeMethod(
      this,
      [outcome, done = std::move(done)] {
        if (done) done(outcome);
      },
      Qt::QueuedConnection);
}

}  // namespace kapfix::station
