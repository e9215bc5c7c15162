#include "agent/commands/calibration_store.hpp"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "common/io/atomic_file.hpp"

namespace kapfix::agent {
namespace {

bool IsSafeFileName(const std::string& name) {
  return !name.empty() && name.size() <= 64 && name.front() != '.' &&
         std::all_of(name.begin(), name.end(), [](char c) {
           return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                  c == '.' || c == '_' || c == '-';
         });
}

}  // namespace

CalibrationStore::CalibrationStore(std::filesystem::path dir) : dir_(std::move(dir)) {}

std::filesystem::path CalibrationStore::PathOf(const std::string& lens) const {
  return dir_ / (lens + ".json");
}

void CalibrationStore::Save(const std::string& lens, const LensCalibration& calibration,
                            const kapfix::v1::CalibrationReport& report) const {
  if (!IsSafeFileName(lens)) {
    throw std::runtime_error("lens name '" + lens + "' is not usable as a file name");
  }
  const nlohmann::json json = {
      {"lens", lens},
      {"pan_deg_per_px", calibration.pan_deg_per_px},
      {"tilt_deg_per_px", calibration.tilt_deg_per_px},
      {"pan_residual_px", report.pan().residual_px()},
      {"tilt_residual_px", report.tilt().residual_px()},
      {"pan_samples", report.pan().samples()},
      {"tilt_samples", report.tilt().samples()},
      {"saved_unix_s", std::chrono::duration_cast<std::chrono::seconds>(
                           std::chrono::system_clock::now().time_since_epoch())
                           .count()},
  };
  std::filesystem::create_directories(dir_);
  WriteFileAtomically(PathOf(lens), json.dump(2) + "\n");
}

std::optional<LensCalibration> CalibrationStore::Load(const std::string& lens,
                                                      std::string* error) const {
  if (error) error->clear();
  if (!IsSafeFileName(lens)) return std::nullopt;
  const std::filesystem::path path = PathOf(lens);
  std::ifstream in(path);
  if (!in) return std::nullopt;
  const nlohmann::json json = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  LensCalibration calibration;
  if (json.is_object() && json.contains("pan_deg_per_px") && json.contains("tilt_deg_per_px") &&
      json["pan_deg_per_px"].is_number() && json["tilt_deg_per_px"].is_number()) {
    calibration.pan_deg_per_px = json["pan_deg_per_px"].get<double>();
    calibration.tilt_deg_per_px = json["tilt_deg_per_px"].get<double>();
    std::string why;
    if (calibration.IsValid(&why)) return calibration;
    if (error) *error = path.string() + ": " + why;
    return std::nullopt;
  }
  if (error) *error = path.string() + ": not a calibration file";
  return std::nullopt;
}

}  // namespace kapfix::agent
