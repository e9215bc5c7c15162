// `kapfix-ctl resync`: what a station asks for when the link comes back (as the Qt station's
// LinkResync): the agent's state, its latest SSP result again, and every stored photo taken at
// or after --photos-since-us, which are saved in --save. The reply names those photos, so we
// know when we have caught up; other photos that arrive meanwhile (taken now) are kept too.
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>

#include "kapfix/v1/photo.pb.h"
#include "kapfix/v1/slices.pb.h"
#include "kapfix/v1/telemetry.pb.h"
#include "link/photo_assembler.hpp"
#include "link/topic_names.hpp"
#include "tools/ctl/commands/command.hpp"
#include "tools/ctl/commands/command_link.hpp"
#include "tools/ctl/commands/command_output.hpp"
#include "tools/ctl/commands/inbox.hpp"
#include "tools/ctl/commands/interrupt.hpp"
#include "tools/ctl/message_text.hpp"
#include "tools/ctl/photo_saving.hpp"

namespace kapfix::ctl {
namespace {

struct ResyncArguments {
  std::int64_t photos_since_us = 0;  // [µs since epoch]
  std::string save_folder;
};

// What the I/O thread hands over while we catch up. Declared before the client: its I/O
// thread uses them until the client is destroyed.
struct ResyncInboxes {
  kapfix::link::PhotoAssembler assembler;  // used on the I/O thread only
  Inbox<kapfix::link::AssembledPhoto> photos;
  Inbox<kapfix::v1::SliceReport> reports;
  std::mutex telemetry_mutex;  // guards latest_telemetry
  std::optional<kapfix::v1::Telemetry> latest_telemetry;
};

// Waits until the SSP result (if the reply says there is one) and every photo the reply names
// have arrived, counting the photos saved in `*saved`; returns the exit code.
int CatchUp(kapfix::link::AgentLinkClient& client, const LinkArguments& link,
            const std::string& save_folder, const kapfix::v1::Reply& reply, ResyncInboxes& inboxes,
            std::size_t* saved) {
  // The agent republishes its SSP result only when it has one.
  bool report_pending = reply.state().has_last_slice_report();
  std::set<std::string> missing(reply.photos_resent().begin(), reply.photos_resent().end());
  const auto deadline = Clock::now() + link.timeout();
  while (report_pending || !missing.empty()) {
    if (Interrupted()) return kNoAnswer;
    if (Clock::now() >= deadline || !client.Status().up) {
      Error("resync incomplete: " + std::to_string(missing.size()) + " of " +
            std::to_string(reply.photos_resent_size()) + " photos" +
            (report_pending ? " and the SSP result" : "") + " not received within " +
            std::to_string(link.timeout_ms) + " ms");
      return kNoAnswer;
    }
    if (const auto report = inboxes.reports.Take(std::chrono::milliseconds(0))) {
      if (report->finished()) {
        PrintLine(SliceReportText(*report));
        report_pending = false;
      }
    }
    if (const auto photo = inboxes.photos.Take(std::chrono::milliseconds(20))) {
      try {
        PrintLine("photo " + kapfix::link::SavePhotoWithSidecar(*photo, save_folder).string());
      } catch (const std::exception& error) {
        Error(error.what());
        return kBadArguments;
      }
      missing.erase(photo->metadata.file_name());
      ++*saved;
    }
  }
  return kOk;
}

int RunResync(const LinkArguments& link, const ResyncArguments& arguments) {
  const auto start = Clock::now();
  const std::string& save_folder = arguments.save_folder;
  if (std::string why;
      !save_folder.empty() && !kapfix::link::PrepareSaveFolder(save_folder, &why)) {
    Error("--save: " + why);
    return kBadArguments;
  }
  ResyncInboxes inboxes;
  auto client = MakeClient(link);
  if (!save_folder.empty()) {
    client->OnMessage(
        std::string(kapfix::link::kPhotoTopic), [&](const google::protobuf::Message& message) {
          if (auto photo = inboxes.assembler.Add(static_cast<const kapfix::v1::Photo&>(message))) {
            inboxes.photos.Put(*photo);
          }
        });
  }
  client->OnMessage(std::string(kapfix::link::kSlicesTopic),
                    [&](const google::protobuf::Message& message) {
                      inboxes.reports.Put(static_cast<const kapfix::v1::SliceReport&>(message));
                    });
  // Telemetry flows with every frame: subscribed to it, StreamsReady returns within a frame
  // instead of waiting up to a second for the agent's heartbeat. Its latest line is printed.
  client->OnMessage(std::string(kapfix::link::kTelemetryTopic),
                    [&](const google::protobuf::Message& message) {
                      const std::lock_guard lock(inboxes.telemetry_mutex);
                      inboxes.latest_telemetry = static_cast<const kapfix::v1::Telemetry&>(message);
                    });
  client->Start();
  if (!StreamsReady(*client, link)) return LinkDown(*client, link);
  if (!save_folder.empty()) inboxes.photos.Arm();
  inboxes.reports.Arm();
  kapfix::v1::Command command;
  command.mutable_request_state()->set_resend_photos_since_us(arguments.photos_since_us);
  command.mutable_request_state()->set_resend_slice_report(true);
  kapfix::v1::Reply reply;
  int code = Send(*client, link, std::move(command), &reply);
  if (code != kOk) return code;
  std::cout << StateText(reply.state());
  std::cout.flush();

  std::size_t saved = 0;
  code = CatchUp(*client, link, save_folder, reply, inboxes, &saved);
  if (code != kOk) return code;
  {
    const std::lock_guard lock(inboxes.telemetry_mutex);
    if (inboxes.latest_telemetry) PrintLine(TelemetryText(*inboxes.latest_telemetry));
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  PrintLine("resync photos_resent=" + std::to_string(reply.photos_resent_size()) +
            " photos_saved=" + std::to_string(saved) + " seconds=" + SecondsText(seconds));
  return kOk;
}

}  // namespace

void AddResyncCommand(CLI::App& app, const LinkArguments& link, CommandRun* run) {
  auto arguments = std::make_shared<ResyncArguments>();
  auto* resync = app.add_subcommand(
      "resync", "catch up after a link loss: state, latest SSP result, photos taken meanwhile");
  auto* resync_save = resync->add_option("--save", arguments->save_folder,
                                         "save the photos the agent sends again in this folder");
  resync
      ->add_option("--photos-since-us", arguments->photos_since_us,
                   "[µs since epoch] ask again for the photos taken at or after this time "
                   "(default 0: none)")
      ->check(CLI::NonNegativeNumber)
      ->needs(resync_save);
  resync->callback([&link, run, arguments] {
    *run = [&link, arguments] { return RunResync(link, *arguments); };
  });
}

}  // namespace kapfix::ctl
