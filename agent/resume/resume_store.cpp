#include "agent/resume/resume_store.hpp"

#include <google/protobuf/util/json_util.h>

#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "common/io/atomic_file.hpp"

namespace kapfix::agent {
namespace {

constexpr int kFormat = 1;  // resume.json's layout; another value is refused
constexpr std::string_view kReferencePrefix = "reference-";

bool IsReferenceName(const std::string& name) {
  return name.starts_with(kReferencePrefix) && name.ends_with(".png") &&
         name.find('/') == std::string::npos && name.find("..") == std::string::npos;
}

}  // namespace

ResumeStore::ResumeStore(std::filesystem::path dir) : dir_(std::move(dir)) {}

void ResumeStore::Save(const ResumeRecord& record) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec) throw std::runtime_error("cannot create " + dir_.string() + ": " + ec.message());
  nlohmann::json json = {
      {"format", kFormat}, {"mode", std::string(ToString(record.mode))}, {"slice", record.slice}};
  nlohmann::json settings = nlohmann::json::array();
  for (const kapfix::v1::Command& command : record.settings) {
    std::string text;
    if (!google::protobuf::util::MessageToJsonString(command, &text).ok()) {
      throw std::runtime_error("a settings command does not convert to JSON");
    }
    settings.push_back(nlohmann::json::parse(text));
  }
  json["settings"] = std::move(settings);
  if (!record.reference_frame.empty()) {
    const bool written = written_reference_.data == record.reference_frame.data &&
                         written_reference_.size() == record.reference_frame.size();
    if (!written) {
      std::vector<unsigned char> png;
      if (!cv::imencode(".png", record.reference_frame, png)) {
        throw std::runtime_error("the reference frame does not encode as PNG");
      }
      const auto now = std::chrono::system_clock::now().time_since_epoch();
      const std::string name =
          std::string(kReferencePrefix) +
          std::to_string(std::chrono::duration_cast<std::chrono::microseconds>(now).count()) +
          ".png";
      WriteFileAtomically(dir_ / name,
                          std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
      written_reference_ = record.reference_frame;
      written_reference_name_ = name;
    }
    json["reference"] = {{"image", written_reference_name_},
                         {"width", record.reference_frame.cols},
                         {"height", record.reference_frame.rows},
                         {"pan_deg", record.reference_at.pan_deg},
                         {"tilt_deg", record.reference_at.tilt_deg}};
  }
  WriteFileAtomically(file(), json.dump(2) + "\n");
  // Older reference images are no longer named by the record (or never were: a crash between
  // the image and the JSON).
  for (const auto& entry : std::filesystem::directory_iterator(dir_, ec)) {
    const std::string name = entry.path().filename().string();
    if (IsReferenceName(name) &&
        (record.reference_frame.empty() || name != written_reference_name_)) {
      std::filesystem::remove(entry.path(), ec);
    }
  }
}

std::optional<ResumeRecord> ResumeStore::Load(std::string* error) {
  if (error) error->clear();
  const std::filesystem::path path = file();
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;  // nothing stored: a first start
  std::stringstream text;
  text << in.rdbuf();
  auto fail = [&](const std::string& why) -> std::optional<ResumeRecord> {
    if (error) *error = path.string() + ": " + why;
    return std::nullopt;
  };
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::exception& e) {
    return fail(std::string("not valid JSON (truncated or corrupt?): ") + e.what());
  }
  ResumeRecord record;
  try {
    if (!json.is_object() || json.value("format", 0) != kFormat) {
      return fail("not a resume record of format " + std::to_string(kFormat));
    }
    const std::string mode = json.at("mode").get<std::string>();
    const std::optional<AgentMode> parsed = ParseAgentMode(mode);
    if (!parsed) return fail("unknown mode '" + mode + "'");
    record.mode = *parsed;
    record.slice = json.at("slice").get<int>();
    for (const nlohmann::json& item : json.at("settings")) {
      kapfix::v1::Command command;
      const auto status = google::protobuf::util::JsonStringToMessage(item.dump(), &command);
      if (!status.ok()) {
        return fail("settings command " + item.dump() +
                    " does not parse: " + std::string(status.message()));
      }
      record.settings.push_back(std::move(command));
    }
    if (json.contains("reference")) {
      const nlohmann::json& reference = json.at("reference");
      const std::string name = reference.at("image").get<std::string>();
      if (!IsReferenceName(name)) return fail("reference image name '" + name + "' refused");
      const cv::Mat frame = cv::imread((dir_ / name).string(), cv::IMREAD_COLOR);
      const int width = reference.at("width").get<int>();
      const int height = reference.at("height").get<int>();
      if (frame.empty()) return fail("reference image " + name + " missing or unreadable");
      if (frame.cols != width || frame.rows != height) {
        return fail("reference image " + name + " is " + std::to_string(frame.cols) + "x" +
                    std::to_string(frame.rows) + ", the record says " + std::to_string(width) +
                    "x" + std::to_string(height));
      }
      record.reference_frame = frame;
      record.reference_at = {reference.at("pan_deg").get<double>(),
                             reference.at("tilt_deg").get<double>()};
      written_reference_ = frame;
      written_reference_name_ = name;
    }
  } catch (const nlohmann::json::exception& e) {
    return fail(std::string("a field is missing or of the wrong type: ") + e.what());
  }
  return record;
}

std::filesystem::path ResumeStore::SetAside() const {
  std::filesystem::path aside = file();
  aside += ".bad";
  std::error_code ec;
  std::filesystem::rename(file(), aside, ec);
  return ec ? std::filesystem::path() : aside;
}

}  // namespace kapfix::agent
