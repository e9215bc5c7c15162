#pragma once

// The Photos tab's table (issue 13): one row per photo with the quality the agent measured at
// capture — residual offset, view speed, blur during the exposure, sharpness, confidence and
// lock, the shutter mode with its wait and reason, the camera (and why another one took it) —
// sortable by any column (numbers sort as numbers), and blurred or off-target photos flagged
// in red (photo_quality.hpp says when).

#include <QTableWidget>

#include "groundstation/photos/photo_store.hpp"

namespace kapfix::station {

class PhotoQualityTable final : public QTableWidget {
  Q_OBJECT

 public:
  enum Column {
    kName,
    kOffset,
    kSpeed,
    kBlur,
    kSharpnessPatch,
    kSharpnessFrame,
    kConfidence,
    kLock,
    kShutter,
    kWait,
    kCamera,
    kFlags,
    kColumns
  };

  explicit PhotoQualityTable(QWidget* parent = nullptr);

  // Adds `photo`'s row; a photo already shown (resent after a link loss) is not added again.
  void addPhoto(const SavedPhoto& photo);
  // The row showing the photo `file_name`; -1 when none.
  int rowOf(const QString& file_name) const;
  // The flags of a row ("BLURRED (…)", "OFF TARGET (…)"), empty when none.
  QString flagsOf(int row) const;
  bool flagged(int row) const { return !flagsOf(row).isEmpty(); }
};

}  // namespace kapfix::station
