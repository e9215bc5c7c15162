#pragma once

// The operator's word for each agent mode.

#include <QString>

#include "kapfix/v1/types.pb.h"

namespace kapfix::station {

QString ModeName(kapfix::v1::Mode mode);

}  // namespace kapfix::station
