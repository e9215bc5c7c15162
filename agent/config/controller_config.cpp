#include "agent/config/controller_config.hpp"

#include "kapfix/v1/settings.pb.h"
#include "kapfix/v1/settings_schema.hpp"

namespace kapfix::agent {

std::optional<ControllerKind> ParseControllerKind(std::string_view text) {
  if (text == "p") return ControllerKind::kP;
  if (text == "pid") return ControllerKind::kPid;
  if (text == "predictive") return ControllerKind::kPredictive;
  return std::nullopt;
}

std::string_view ToString(ControllerKind kind) {
  switch (kind) {
    case ControllerKind::kP:
      return "p";
    case ControllerKind::kPid:
      return "pid";
    case ControllerKind::kPredictive:
      return "predictive";
  }
  return "?";
}

bool ControllerConfig::IsValid(std::string* error) const {
  // The ranges are the schema's (kapfix.v1.Gains), shared with the command validator.
  const auto& gains = *kapfix::v1::Gains::descriptor();
  for (const auto& [field, value, name] :
       {std::tuple{"p", kp, "controller.kp"}, std::tuple{"i", ki, "controller.ki"},
        std::tuple{"d", kd, "controller.kd"},
        std::tuple{"dead_band_px", dead_band_px, "controller.dead_band_px"},
        std::tuple{"rate_limit_deg_per_s", max_rate_deg_per_s, "controller.max_rate_deg_per_s"}}) {
    std::string reason = kapfix::v1::CheckSetting(gains, field, value, name);
    if (!reason.empty()) {
      if (error) *error = std::move(reason);
      return false;
    }
  }
  return true;
}

}  // namespace kapfix::agent
