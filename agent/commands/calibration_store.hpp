#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "common/control/lens_calibration.hpp"
#include "kapfix/v1/calibration.pb.h"

namespace kapfix::agent {

// Calibrations stored per lens profile (SPEC §2.7), so that a restarted agent flies with the
// deg/px it measured, not the profile's nominal one: DIR/LENS.json, written atomically. Lens
// names are checked by the command validator (no path separators); a name that is not safe as
// a file name is neither saved nor loaded.
class CalibrationStore {
 public:
  explicit CalibrationStore(std::filesystem::path dir);

  // Throws std::runtime_error naming the file when it cannot be written.
  void Save(const std::string& lens, const LensCalibration& calibration,
            const kapfix::v1::CalibrationReport& report) const;
  // The stored calibration of `lens`; nullopt when none is stored or the file is unreadable
  // (`error` then says why; empty when there simply is none).
  std::optional<LensCalibration> Load(const std::string& lens, std::string* error) const;

 private:
  std::filesystem::path PathOf(const std::string& lens) const;
  std::filesystem::path dir_;
};

}  // namespace kapfix::agent
