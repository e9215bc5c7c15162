#pragma once

// The one way the station's panels reach an agent (SPEC §5, §6): streams arrive as typed
// signals, commands leave through sendCommand() and come back as a CommandOutcome. Every
// signal is emitted on the GUI thread and every callback runs there, so a panel never
// locks anything. Implementations: ZmqAgentClient (the live link), FakeAgentClient (tests),
// ReplayAgentClient (a recorded session) and SwitchableAgentClient (what the views watch).
//
// Messages are decoded in one place, deliverMessage(), whatever their source: the live link,
// a recording or a test all go through the same checks (size, header, protocol version).

#include <QByteArray>
#include <QObject>
#include <QString>
#include <cstdint>
#include <functional>
#include <string_view>

#include "kapfix/v1/calibration.pb.h"
#include "kapfix/v1/command.pb.h"
#include "kapfix/v1/log.pb.h"
#include "kapfix/v1/photo.pb.h"
#include "kapfix/v1/slices.pb.h"
#include "kapfix/v1/state.pb.h"
#include "kapfix/v1/telemetry.pb.h"
#include "kapfix/v1/video.pb.h"

namespace kapfix::station {

// What the status bar shows about the link.
struct LinkState {
  bool up = false;                  // the agent was heard within the link timeout
  bool replay = false;              // the views show a recording, not a live agent
  QString source;                   // endpoint, or the replayed file
  QString agent_id;                 // as the agent's messages say; empty = not heard yet
  std::int64_t latency_us = -1;     // [µs] heartbeat round trip; -1 = none measured
  std::uint64_t sequence_gaps = 0;  // [count] stream messages lost on the link
  QString handshake_failure;        // why the agent would not let this station in; empty = none

  bool operator==(const LinkState&) const = default;
};

// How a command ended.
struct CommandOutcome {
  bool answered = false;  // a reply came back in time
  bool ok = false;        // and it accepted the command
  QString reason;         // why not, for the operator: the agent's words, or ours
  kapfix::v1::Reply reply;
};

class AgentClient : public QObject {
  Q_OBJECT

 public:
  using ReplyCallback = std::function<void(const CommandOutcome& outcome)>;

  explicit AgentClient(QObject* parent = nullptr);
  ~AgentClient() override;
  AgentClient(const AgentClient&) = delete;
  AgentClient& operator=(const AgentClient&) = delete;

  // Sends `command` (its header is the client's to stamp). `done`, if given, runs exactly
  // once on the GUI thread, never from inside this call.
  virtual void sendCommand(kapfix::v1::Command command, ReplyCallback done = {}) = 0;
  virtual LinkState linkState() const = 0;

 signals:
  void linkChanged(const kapfix::station::LinkState& state);
  void telemetryReceived(const kapfix::v1::Telemetry& telemetry);
  void videoFrameReceived(const kapfix::v1::VideoFrame& frame);
  void sliceReportReceived(const kapfix::v1::SliceReport& report);
  void pssReportReceived(const kapfix::v1::PssReport& report);
  void calibrationReceived(const kapfix::v1::CalibrationReport& report);
  void stateReceived(const kapfix::v1::AgentState& state);
  void photoChunkReceived(const kapfix::v1::Photo& chunk);
  void logReceived(const kapfix::v1::Log& line);
  // The session's events: what the operator commanded and what the agent answered.
  void commandSent(const kapfix::v1::Command& command);
  void replyReceived(const kapfix::v1::Reply& reply);
  // Every message above, as bytes on the link (topic, serialized message), for recording.
  // receiveTimeUs [µs since epoch, this side's clock].
  void messageReceived(const QString& topic, const QByteArray& payload, qint64 receiveTimeUs);

 protected:
  // Decodes one message of `topic` and emits messageReceived plus its typed signal
  // (heartbeats are consumed by the link and not emitted). False when it does not decode.
  bool deliverMessage(std::string_view topic, std::string_view payload,
                      std::int64_t receive_time_us);
  // Announces a command about to leave (commandSent, and its bytes for recording).
  void announceCommand(const kapfix::v1::Command& command);
  // Announces the outcome (replyReceived, stateReceived when the reply carries a state) and
  // runs `done`.
  void finishCommand(const CommandOutcome& outcome, const ReplyCallback& done);
};

}  // namespace kapfix::station
