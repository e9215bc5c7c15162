// `kapfix-ctl photo`: take a stabilised photo on the agent, optionally receiving and saving it.
#include <filesystem>
#include <memory>
#include <string>

#include "kapfix/v1/photo.pb.h"
#include "link/photo_assembler.hpp"
#include "link/topic_names.hpp"
#include "tools/ctl/commands/command.hpp"
#include "tools/ctl/commands/command_link.hpp"
#include "tools/ctl/commands/command_output.hpp"
#include "tools/ctl/commands/inbox.hpp"
#include "tools/ctl/commands/interrupt.hpp"
#include "tools/ctl/photo_saving.hpp"

namespace kapfix::ctl {
namespace {

struct PhotoArguments {
  std::string save_folder;
  std::string note;
};

int RunPhoto(const LinkArguments& link, const PhotoArguments& arguments) {
  kapfix::v1::Command command;
  command.mutable_take_photo()->set_note(arguments.note);
  if (arguments.save_folder.empty()) return RunSimple(link, std::move(command));

  if (std::string why; !kapfix::link::PrepareSaveFolder(arguments.save_folder, &why)) {
    Error("--save: " + why);
    return kBadArguments;
  }
  // Before the client: its I/O thread uses them until the client is destroyed.
  kapfix::link::PhotoAssembler assembler;  // used on the I/O thread only
  Inbox<kapfix::link::AssembledPhoto> photos;
  auto client = MakeClient(link);
  client->OnMessage(
      std::string(kapfix::link::kPhotoTopic), [&](const google::protobuf::Message& message) {
        if (auto photo = assembler.Add(static_cast<const kapfix::v1::Photo&>(message))) {
          photos.Put(*photo);
        }
      });
  client->Start();
  if (!StreamsReady(*client, link)) return LinkDown(*client, link);
  photos.Arm();
  const int code = Send(*client, link, std::move(command));
  if (code != kOk) return code;
  while (!Interrupted()) {
    if (const auto photo = photos.Take(std::chrono::milliseconds(50))) {
      try {
        PrintLine(kapfix::link::SavePhotoWithSidecar(*photo, arguments.save_folder).string());
      } catch (const std::exception& error) {
        Error(error.what());
        return kBadArguments;
      }
      return kOk;
    }
    if (!client->Status().up) return LinkDown(*client, link);
  }
  return kOk;
}

}  // namespace

void AddPhotoCommand(CLI::App& app, const LinkArguments& link, CommandRun* run) {
  auto arguments = std::make_shared<PhotoArguments>();
  auto* photo = app.add_subcommand("photo", "take a stabilised photo on the agent");
  photo->add_option("--save", arguments->save_folder,
                    "also receive it and save it with its JSON sidecar in this folder (made "
                    "when missing)");
  photo->add_option("--note", arguments->note, "text stored in the photo's sidecar");
  photo->callback([&link, run, arguments] {
    *run = [&link, arguments] { return RunPhoto(link, *arguments); };
  });
}

}  // namespace kapfix::ctl
