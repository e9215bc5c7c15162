#pragma once

// The live link: AgentClient over kapfix::link::AgentLinkClient (ZeroMQ + Protobuf). The
// link client's handlers run on its I/O thread; they only copy bytes and post them to the
// GUI thread, so neither side ever waits for the other. Video is coalesced on the way: only
// the newest frame waits for the GUI, so a slow GUI drops stale frames instead of falling
// behind (telemetry and everything else is delivered in order, never dropped here).
//
// Reconnection is the link's (ZeroMQ reconnects by itself); connectTo() switches agents.

#include <QTimer>
#include <chrono>
#include <memory>
#include <optional>

#include "groundstation/client/agent_address.hpp"
#include "groundstation/client/agent_client.hpp"
#include "link/curve_key_pair.hpp"

namespace kapfix::link {
class AgentLinkClient;
}

namespace kapfix::station {

struct ZmqAgentClientOptions {
  std::chrono::milliseconds command_timeout{3000};  // [ms] a command with no reply fails
  std::chrono::milliseconds link_timeout{3000};     // [ms] silence before the link is down
  std::chrono::milliseconds heartbeat_interval{1000};
  std::chrono::milliseconds status_poll{250};  // [ms] how often latency is refreshed
  // CurveZMQ keys (--key, --agent-key); unset: plain, for an agent on this machine.
  std::optional<kapfix::link::CurveClientKeys> curve;
};

class ZmqAgentClient final : public AgentClient {
  Q_OBJECT

 public:
  explicit ZmqAgentClient(ZmqAgentClientOptions options = {}, QObject* parent = nullptr);
  ~ZmqAgentClient() override;

  // Drops the current link (pending commands fail) and connects to `address`. Returns false
  // with `error` set when the address is not one ZeroMQ accepts.
  bool connectTo(const AgentAddress& address, QString* error = nullptr);
  // Same, with explicit ZeroMQ endpoints (e.g. from tests on ephemeral ports).
  bool connectToEndpoints(const QString& command_endpoint, const QString& stream_endpoint,
                          QString* error = nullptr);
  void disconnectFromAgent();

  void sendCommand(kapfix::v1::Command command, ReplyCallback done = {}) override;
  LinkState linkState() const override;

 private:
  struct VideoSlot;
  void stopLink();
  void refreshLinkState();
  void drainVideo(const std::shared_ptr<VideoSlot>& slot);

  ZmqAgentClientOptions options_;
  std::unique_ptr<kapfix::link::AgentLinkClient> link_;
  std::uint64_t generation_ = 0;  // which link a posted message came from
  QString source_;
  LinkState state_;
  QTimer status_timer_;
};

}  // namespace kapfix::station
