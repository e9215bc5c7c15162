// kapfix-station: the operator's ground station (SPEC §6, issue 4). Parses the command line
// and wires the parts together; each part lives in its own folder.
#include <QApplication>
#include <QCommandLineParser>
#include <QSettings>
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>

#include "groundstation/client/agent_address.hpp"
#include "groundstation/client/link_resync.hpp"
#include "groundstation/client/zmq_agent_client.hpp"
#include "groundstation/main_window.hpp"
#include "groundstation/photos/photo_store.hpp"
#include "groundstation/photos/photos_panel.hpp"
#include "groundstation/recording/recording_controls.hpp"
#include "groundstation/snapshot/ssp_screenshot.hpp"
#include "groundstation/status/connection_bar.hpp"
#include "kapfix/v1/envelope_codec.hpp"
#include "link/curve_key_file.hpp"

namespace {

constexpr double kDefaultFontPt = 11.5;  // [pt] readable at arm's length on a laptop
constexpr std::int64_t kResyncHorizonUs = 3600LL * 1'000'000;  // [µs] one flight, at most

// The command line's options, declared once.
struct StationCommandLine {
  QCommandLineOption agent{{QStringLiteral("a"), QStringLiteral("agent")},
                           QStringLiteral("Agent host (default: the last one used)."),
                           QStringLiteral("host")};
  QCommandLineOption command_port{QStringLiteral("command-port"),
                                  QStringLiteral("Agent command port (default 5555)."),
                                  QStringLiteral("port")};
  QCommandLineOption stream_port{QStringLiteral("stream-port"),
                                 QStringLiteral("Agent stream port (default 5556)."),
                                 QStringLiteral("port")};
  QCommandLineOption replay{QStringLiteral("replay"),
                            QStringLiteral("Replay a recorded session instead of the agent."),
                            QStringLiteral("file")};
  QCommandLineOption screenshot{
      QStringLiteral("screenshot"),
      QStringLiteral("Save the window as PNG once SSP results are shown, then quit."),
      QStringLiteral("file")};
  QCommandLineOption run_ssp{QStringLiteral("run-ssp"),
                             QStringLiteral("With --screenshot: start SSP when the link is up.")};
  QCommandLineOption fixate{
      QStringLiteral("fixate"),
      QStringLiteral("With --screenshot: confirm the recommended slice and take the picture "
                     "while fixating.")};
  QCommandLineOption size{QStringLiteral("size"),
                          QStringLiteral("Window size WxH [px], e.g. 1366x768."),
                          QStringLiteral("WxH")};
  QCommandLineOption font_size{QStringLiteral("font-size"),
                               QStringLiteral("Text size [pt] (default 11.5)."),
                               QStringLiteral("pt")};
  QCommandLineOption key{
      QStringLiteral("key"),
      QStringLiteral("This station's secret key file (kapfix-keygen); with --agent-key the link "
                     "uses CurveZMQ."),
      QStringLiteral("file")};
  QCommandLineOption agent_key{QStringLiteral("agent-key"),
                               QStringLiteral("The agent's public key file (its .pub)."),
                               QStringLiteral("file")};

  void AddTo(QCommandLineParser& parser) const {
    parser.addOptions({agent, command_port, stream_port, replay, screenshot, run_ssp, fixate, size,
                       font_size, key, agent_key});
  }
};

// --key and --agent-key into `options` (CurveZMQ); false, said on stderr, when they are not
// both given or a key file cannot be read.
bool ReadCurveKeys(const QCommandLineParser& parser, const StationCommandLine& cli,
                   kapfix::station::ZmqAgentClientOptions* options) {
  if (parser.isSet(cli.key) != parser.isSet(cli.agent_key)) {
    std::fprintf(stderr, "kapfix-station: --key and --agent-key go together\n");
    return false;
  }
  if (!parser.isSet(cli.key)) return true;
  std::string why;
  const auto station = kapfix::link::ReadSecretKeyFile(parser.value(cli.key).toStdString(), &why);
  const auto agent_public =
      station ? kapfix::link::ReadPublicKeyFile(parser.value(cli.agent_key).toStdString(), &why)
              : std::nullopt;
  if (!agent_public) {
    std::fprintf(stderr, "kapfix-station: %s\n", why.c_str());
    return false;
  }
  options->curve = kapfix::link::CurveClientKeys{*station, *agent_public};
  return true;
}

// --size WxH; false, said on stderr, when it is not a size of at least 320×240.
bool ApplyWindowSize(const QCommandLineParser& parser, const StationCommandLine& cli,
                     QWidget& window) {
  if (!parser.isSet(cli.size)) return true;
  const QStringList wh = parser.value(cli.size).split(QLatin1Char('x'));
  const int w = wh.value(0).toInt();
  const int h = wh.value(1).toInt();
  if (wh.size() != 2 || w < 320 || h < 240) {
    std::fprintf(stderr, "kapfix-station: --size wants WxH of at least 320x240, e.g. 1366x768\n");
    return false;
  }
  window.resize(w, h);
  return true;
}

// The agent's address: the last one used, with what the command line changes.
void ConnectToAgent(const QCommandLineParser& parser, const StationCommandLine& cli,
                    kapfix::station::ConnectionBar& connection) {
  kapfix::station::AgentAddress address = connection.address();
  if (parser.isSet(cli.agent)) address.host = parser.value(cli.agent);
  if (parser.isSet(cli.command_port)) address.command_port = parser.value(cli.command_port).toInt();
  if (parser.isSet(cli.stream_port)) address.stream_port = parser.value(cli.stream_port).toInt();
  connection.setAddress(address);
  connection.connectToAgent();
}

}  // namespace

int main(int argc, char** argv) {
  QApplication app(argc, argv);
  QApplication::setOrganizationName(QStringLiteral("kapfix"));
  QApplication::setApplicationName(QStringLiteral("kapfix-station"));
  QApplication::setApplicationVersion(QStringLiteral(KAPFIX_VERSION));
  QApplication::setStyle(QStringLiteral("Fusion"));

  QCommandLineParser parser;
  parser.setApplicationDescription(QStringLiteral("kapfix ground station"));
  parser.addHelpOption();
  parser.addVersionOption();
  const StationCommandLine cli;
  cli.AddTo(parser);
  parser.process(app);

  kapfix::station::ZmqAgentClientOptions client_options;
  if (!ReadCurveKeys(parser, cli, &client_options)) return 2;

  QFont font = QApplication::font();
  font.setPointSizeF(parser.isSet(cli.font_size) ? parser.value(cli.font_size).toDouble()
                                                 : kDefaultFontPt);
  QApplication::setFont(font);

  using namespace kapfix::station;
  ZmqAgentClient live(client_options);
  // The window's toolbar takes ownership of these two. A replay opens a window of its own.
  auto* connection = new ConnectionBar(live);
  auto* recording = new RecordingControls(live);
  MainWindow window({&live, connection, recording});
  if (!ApplyWindowSize(parser, cli, window)) return 2;
  // A restarted station catches up from the newest photo it already holds, so photos the agent
  // took while no station was running arrive too; not from further back than kResyncHorizon
  // (an old folder holds other flights, not this one's).
  const std::int64_t start_us = kapfix::v1::NowMicros();
  const std::int64_t newest_held_us = PhotoStore::newestCaptureTimeUs(window.photos().folder());
  const LinkResync resync(live, std::max(newest_held_us + 1, start_us - kResyncHorizonUs));
  ConnectToAgent(parser, cli, *connection);

  if (parser.isSet(cli.replay)) {
    QString error;
    if (!recording->startReplay(parser.value(cli.replay), &error)) {
      std::fprintf(stderr, "kapfix-station: %s\n", error.toLocal8Bit().constData());
      return 2;
    }
  }
  std::optional<SspScreenshot> snapshot;
  if (parser.isSet(cli.screenshot)) {
    SspScreenshotOptions options;
    options.path = parser.value(cli.screenshot);
    options.run_ssp = parser.isSet(cli.run_ssp);
    options.fixate = parser.isSet(cli.fixate);
    snapshot.emplace(window, live, window.ssp(), options);
  }
  window.show();
  return QApplication::exec();
}
