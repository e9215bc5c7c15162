#include "link/zap_handler.hpp"

#include <spdlog/spdlog.h>
#include <zmq.h>

#include <array>
#include <chrono>
#include <future>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <vector>

#include "link/whole_message_receive.hpp"

namespace kapfix::link {
namespace {

constexpr const char* kZapEndpoint = "inproc://zeromq.zap.01";
constexpr std::string_view kZapVersion = "1.0";
constexpr std::size_t kCurveKeyBytes = 32;
// ZMQ_ZAP_ENFORCE_DOMAIN: in zmq.h only under the draft API, but the library takes it. Without
// it, libzmq lets a CURVE handshake through when no ZAP handler answers.
constexpr int kZapEnforceDomainOption = 93;
// A station with a wrong key retries every reconnect interval, and a hostile peer can try a
// fresh key per connection: one log line per this period in all, whatever the key or address
// (issue 15, item 11), naming the latest refusal and how many were not logged.
constexpr std::chrono::seconds kRefusalLogPeriod{10};

// ZAP request frames (RFC 27): version, request id, domain, address, identity, mechanism,
// then the mechanism's credentials (CURVE: the client's 32-byte public key).
enum Frame : std::size_t {
  kVersion = 0,
  kRequestId,
  kDomain,
  kAddress,
  kIdentity,
  kMechanism,
  kCredentials,
};

std::string Z85(const zmq::message_t& key) {
  std::array<char, 41> text{};
  if (key.size() != kCurveKeyBytes ||
      zmq_z85_encode(text.data(), static_cast<const std::uint8_t*>(key.data()), key.size()) ==
          nullptr) {
    return {};
  }
  return {text.data(), 40};
}

}  // namespace

void RequireCurve(zmq::socket_t& socket, const CurveServerKeys& keys) {
  socket.set(zmq::sockopt::curve_server, true);
  socket.set(zmq::sockopt::curve_secretkey, keys.secret_key);
  socket.set(zmq::sockopt::zap_domain, kZapDomain);
  const int enforce = 1;
  if (zmq_setsockopt(socket.handle(), kZapEnforceDomainOption, &enforce, sizeof enforce) != 0) {
    throw zmq::error_t();
  }
}

ZapHandler::ZapHandler(const CurveServerKeys& keys, std::string what) : what_(std::move(what)) {
  for (const auto& station : keys.authorized_stations) stations_[station.key] = station.name;
}

ZapHandler::~ZapHandler() { Join(); }

void ZapHandler::Start(zmq::context_t& context) {
  std::promise<void> bound;
  std::future<void> done = bound.get_future();
  thread_ = std::thread([this, &context, promise = std::move(bound)]() mutable {
    zmq::socket_t socket(context, zmq::socket_type::rep);
    try {
      socket.set(zmq::sockopt::linger, 0);
      socket.bind(kZapEndpoint);
    } catch (const zmq::error_t& error) {
      promise.set_exception(std::make_exception_ptr(
          std::runtime_error(what_ + ": cannot start the key check (ZAP): " + error.what())));
      return;
    }
    promise.set_value();
    Serve(socket);
  });
  try {
    done.get();
  } catch (...) {
    thread_.join();
    throw;
  }
}

void ZapHandler::Join() {
  if (thread_.joinable()) thread_.join();
}

ZapHandler::Counters ZapHandler::counters() const { return {accepted_.load(), refused_.load()}; }

bool ZapHandler::Decide(const std::vector<zmq::message_t>& request, std::string* user,
                        std::string* why) const {
  if (request.size() < kCredentials) {
    *why = "malformed ZAP request";
    return false;
  }
  if (request[kDomain].to_string_view() != kZapDomain) {
    *why = "domain '" + request[kDomain].to_string() + "' is not " + kZapDomain;
    return false;
  }
  if (request[kMechanism].to_string_view() != "CURVE" || request.size() != kCredentials + 1) {
    *why = "not CurveZMQ (mechanism " + request[kMechanism].to_string() + ")";
    return false;
  }
  const std::string key = Z85(request[kCredentials]);
  const auto station = stations_.find(key);
  if (key.empty() || station == stations_.end()) {
    *why = "unknown station key " + (key.empty() ? std::string("(malformed)") : key);
    return false;
  }
  *user = station->second.empty() ? key : station->second;
  return true;
}

void ZapHandler::Serve(zmq::socket_t& socket) {
  using Clock = std::chrono::steady_clock;
  Clock::time_point last_logged{};
  std::uint64_t not_logged = 0;  // refusals since the last line
  while (true) {
    std::vector<zmq::message_t> request;
    try {
      // A well-formed request has 7 frames; libzmq is the only sender here.
      (void)link::ReceiveWholeMessage(socket, kCredentials + 1, &request);
    } catch (const zmq::error_t& error) {
      if (error.num() == ETERM) return;
      continue;
    }
    std::string user;
    std::string why;
    const bool ok = Decide(request, &user, &why);
    (ok ? accepted_ : refused_).fetch_add(1);
    const std::string address = request.size() > kAddress ? request[kAddress].to_string() : "";
    if (!ok) {
      if (Clock::now() - last_logged >= kRefusalLogPeriod) {
        spdlog::warn("{}: refused a connection from {}: {}{}", what_, address, why,
                     not_logged == 0
                         ? std::string()
                         : " (and " + std::to_string(not_logged) + " other refusals in the last " +
                               std::to_string(kRefusalLogPeriod.count()) + " s)");
        last_logged = Clock::now();
        not_logged = 0;
      } else {
        ++not_logged;
      }
    }
    const std::string request_id =
        request.size() > kRequestId ? request[kRequestId].to_string() : "";
    const std::array<std::string, 6> reply = {
        std::string(kZapVersion), request_id, ok ? "200" : "400", ok ? "OK" : why, user, ""};
    try {
      for (std::size_t i = 0; i < reply.size(); ++i) {
        (void)socket.send(zmq::buffer(reply[i]),
                          i + 1 < reply.size() ? zmq::send_flags::sndmore : zmq::send_flags::none);
      }
    } catch (const zmq::error_t& error) {
      if (error.num() == ETERM) return;
    }
  }
}

}  // namespace kapfix::link
