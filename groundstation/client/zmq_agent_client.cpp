#include "groundstation/client/zmq_agent_client.hpp"

#include <QMetaObject>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "kapfix/v1/envelope_codec.hpp"
#include "link/agent_link_client.hpp"
#include "link/topic_names.hpp"

namespace kapfix::station {

// The newest video frame not yet handed to the GUI; shared by the I/O thread and the GUI.
struct ZmqAgentClient::VideoSlot {
  std::mutex mutex;
  std::optional<std::string> payload;  // guarded by mutex
  std::int64_t receive_time_us = 0;    // guarded by mutex
};

ZmqAgentClient::ZmqAgentClient(ZmqAgentClientOptions options, QObject* parent)
    : AgentClient(parent), options_(std::move(options)) {
  status_timer_.setInterval(options_.status_poll);
  connect(&status_timer_, &QTimer::timeout, this, &ZmqAgentClient::refreshLinkState);
}

ZmqAgentClient::~ZmqAgentClient() { stopLink(); }

bool ZmqAgentClient::connectTo(const AgentAddress& address, QString* error) {
  return connectToEndpoints(address.commandEndpoint(), address.streamEndpoint(), error);
}

bool ZmqAgentClient::connectToEndpoints(const QString& command_endpoint,
                                        const QString& stream_endpoint, QString* error) {
  stopLink();
  kapfix::link::AgentLinkClientOptions link_options;
  link_options.command_endpoint = command_endpoint.toStdString();
  link_options.stream_endpoint = stream_endpoint.toStdString();
  link_options.link_timeout = options_.link_timeout;
  link_options.heartbeat_interval = options_.heartbeat_interval;
  link_options.curve = options_.curve;
  auto link = std::make_unique<kapfix::link::AgentLinkClient>(link_options);

  const std::uint64_t generation = ++generation_;
  auto video = std::make_shared<VideoSlot>();
  link->OnRawMessage([this, generation, video](std::string_view topic, std::string_view payload) {
    const std::int64_t now_us = kapfix::v1::NowMicros();
    if (topic == kapfix::link::kVideoTopic) {
      bool post = false;
      {
        const std::lock_guard lock(video->mutex);
        post = !video->payload.has_value();
        video->payload.emplace(payload);
        video->receive_time_us = now_us;
      }
      if (post) {
        QMetaObject::invokeMethod(
            this,
            [this, generation, video] {
              if (generation == generation_) drainVideo(video);
            },
            Qt::QueuedConnection);
      }
      return;
    }
    QMetaObject::invokeMethod(
        this,
        [this, generation, topic = std::string(topic), payload = std::string(payload), now_us] {
          if (generation == generation_) deliverMessage(topic, payload, now_us);
        },
        Qt::QueuedConnection);
  });
  link->OnLinkChange([this, generation](bool /*up*/) {
    QMetaObject::invokeMethod(
        this,
        [this, generation] {
          if (generation == generation_) refreshLinkState();
        },
        Qt::QueuedConnection);
  });
  try {
    link->Start();
  } catch (const std::runtime_error& failure) {
    if (error != nullptr) *error = QString::fromStdString(failure.what());
    return false;
  }
  link_ = std::move(link);
  source_ = command_endpoint;
  status_timer_.start();
  refreshLinkState();
  return true;
}

void ZmqAgentClient::disconnectFromAgent() {
  stopLink();
  refreshLinkState();
}

void ZmqAgentClient::stopLink() {
  ++generation_;  // whatever the old link already posted is ignored
  status_timer_.stop();
  if (link_) {
    link_->Stop();  // joins the I/O thread; pending commands end as unanswered
    link_.reset();
  }
  source_.clear();
}

void ZmqAgentClient::drainVideo(const std::shared_ptr<VideoSlot>& slot) {
  std::string payload;
  std::int64_t receive_time_us = 0;
  {
    const std::lock_guard lock(slot->mutex);
    if (!slot->payload) return;
    payload = std::move(*slot->payload);
    slot->payload.reset();
    receive_time_us = slot->receive_time_us;
  }
  deliverMessage(kapfix::link::kVideoTopic, payload, receive_time_us);
}

void ZmqAgentClient::sendCommand(kapfix::v1::Command command, ReplyCallback done) {
  announceCommand(command);
  if (!link_) {
    CommandOutcome outcome;
    outcome.reason = tr("not connected to an agent");
    QMetaObject::invokeMethod(
        this, [this, outcome, done = std::move(done)] { finishCommand(outcome, done); },
        Qt::QueuedConnection);
    return;
  }
  const auto timeout = options_.command_timeout;
  link_->RequestAsync(
      std::move(command), timeout,
      [this, timeout, done = std::move(done)](std::optional<kapfix::v1::Reply> reply) {
        CommandOutcome outcome;
        if (reply) {
          outcome.answered = true;
          outcome.ok = reply->ok();
          outcome.reason = QString::fromStdString(reply->reason());
          outcome.reply = std::move(*reply);
        } else {
          outcome.reason = tr("no answer within %1 ms: link down or no agent")
                               .arg(static_cast<qint64>(timeout.count()));
        }
        // Runs even when the link was replaced meanwhile: every command ends exactly once.
        QMetaObject::invokeMethod(
            this, [this, outcome, done] { finishCommand(outcome, done); }, Qt::QueuedConnection);
      });
}

LinkState ZmqAgentClient::linkState() const { return state_; }

void ZmqAgentClient::refreshLinkState() {
  LinkState state;
  state.source = source_;
  if (link_) {
    const kapfix::link::LinkStatus status = link_->Status();
    state.up = status.up;
    state.agent_id = QString::fromStdString(status.agent_id);
    state.latency_us = status.latency_us;
    state.sequence_gaps = status.sequence_gaps;
    state.handshake_failure = QString::fromStdString(status.handshake_failure);
  }
  if (state == state_) return;
  state_ = state;
  emit linkChanged(state_);
}

}  // namespace kapfix::station
