#include "groundstation/status/mode_name.hpp"

#include <QObject>

namespace kapfix::station {

QString ModeName(kapfix::v1::Mode mode) {
  switch (mode) {
    case kapfix::v1::MODE_IDLE:
      return QObject::tr("Idle");
    case kapfix::v1::MODE_CALIBRATE:
      return QObject::tr("Calibrating");
    case kapfix::v1::MODE_PSS:
      return QObject::tr("PSS");
    case kapfix::v1::MODE_SSP:
      return QObject::tr("SSP");
    case kapfix::v1::MODE_FIXATE:
      return QObject::tr("Fixate");
    case kapfix::v1::MODE_FOLLOW:
      return QObject::tr("Follow");
    case kapfix::v1::MODE_RECORD_FREE_SWING:
      return QObject::tr("Free swing");
    default:
      return QObject::tr("—");
  }
}

}  // namespace kapfix::station
