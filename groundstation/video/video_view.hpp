#pragma once

// The live picture: the agent's JPEG scaled to fit (aspect kept), with the overlays of
// video.proto drawn on top in camera-frame geometry. A click on the picture names the slice
// under it.

#include <QElapsedTimer>
#include <QImage>
#include <QTimer>
#include <QWidget>

#include "groundstation/video/overlay_options.hpp"
#include "kapfix/v1/video.pb.h"

class QPainter;

namespace kapfix::station {

class VideoView final : public QWidget {
  Q_OBJECT

 public:
  explicit VideoView(QWidget* parent = nullptr);

  void showFrame(const kapfix::v1::VideoFrame& frame);
  void setOverlayOptions(const OverlayOptions& options);
  const OverlayOptions& overlayOptions() const { return options_; }
  // Link down: the picture is marked stale, with the age of its frame, until a new frame.
  void setStale(bool stale);
  bool stale() const { return stale_; }
  // What the stale marking says ("" while live).
  QString staleText() const;
  // Forgets the picture (a new session: the old one's frame is not this agent's).
  void clearPicture();
  // A frame whose JPEG did not decode keeps the last picture.
  bool hasPicture() const { return !image_.isNull(); }
  std::uint64_t frameNumber() const { return frame_number_; }

  // [widget px] where the camera frame is drawn.
  QRectF pictureRect() const;
  // [widget px] the centre of slice `index` on screen, e.g. for a click; null point if none.
  QPointF sliceCentre(unsigned index) const;

  QSize sizeHint() const override { return {800, 600}; }
  QSize minimumSizeHint() const override { return {320, 240}; }

 signals:
  void sliceClicked(unsigned index);

 protected:
  void paintEvent(QPaintEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;

 private:
  void paintStale(QPainter& painter, const QRectF& picture);

  QImage image_;
  kapfix::v1::Overlay overlay_;
  double frame_width_px_ = 0;   // [px] camera frame the overlay refers to
  double frame_height_px_ = 0;  // [px]
  std::uint64_t frame_number_ = 0;
  OverlayOptions options_;
  bool stale_ = false;
  QElapsedTimer frame_age_;  // since the picture shown arrived
  QTimer stale_tick_;        // repaints the age while stale
};

}  // namespace kapfix::station
