#include "groundstation/video/video_view.hpp"

#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>

#include "groundstation/video/slice_geometry.hpp"

namespace kapfix::station {
namespace {

QRectF ToRectF(const kapfix::v1::Rect& rect) {
  return {static_cast<double>(rect.x()), static_cast<double>(rect.y()),
          static_cast<double>(rect.width()), static_cast<double>(rect.height())};
}

}  // namespace

VideoView::VideoView(QWidget* parent) : QWidget(parent) {
  setObjectName(QStringLiteral("videoView"));
  setAttribute(Qt::WA_OpaquePaintEvent);
  setCursor(Qt::CrossCursor);
  setToolTip(tr("Click a band of the picture to fixate on that slice"));
  stale_tick_.setInterval(250);  // [ms] the age shown counts up
  connect(&stale_tick_, &QTimer::timeout, this, qOverload<>(&QWidget::update));
}

void VideoView::setStale(bool stale) {
  stale_ = stale;
  if (stale) {
    stale_tick_.start();
  } else {
    stale_tick_.stop();
  }
  update();
}

QString VideoView::staleText() const {
  if (!stale_) return {};
  if (image_.isNull() || !frame_age_.isValid()) return tr("LINK DOWN: no video");
  return tr("STALE: last frame %1 s ago")
      .arg(static_cast<double>(frame_age_.elapsed()) / 1000.0, 0, 'f', 1);
}

void VideoView::clearPicture() {
  image_ = QImage();
  overlay_.Clear();
  frame_number_ = 0;
  update();
}

void VideoView::showFrame(const kapfix::v1::VideoFrame& frame) {
  QImage image;
  if (!image.loadFromData(reinterpret_cast<const uchar*>(frame.jpeg().data()),
                          static_cast<int>(frame.jpeg().size()), "JPEG")) {
    return;
  }
  image_ = std::move(image);
  overlay_ = frame.overlay();
  // The overlay is in camera pixels; without them the JPEG's own size stands in.
  frame_width_px_ = frame.frame_width_px() > 0 ? frame.frame_width_px() : image_.width();
  frame_height_px_ = frame.frame_height_px() > 0 ? frame.frame_height_px() : image_.height();
  frame_number_ = frame.frame_number();
  frame_age_.start();
  setStale(false);
}

void VideoView::setOverlayOptions(const OverlayOptions& options) {
  options_ = options;
  update();
}

QRectF VideoView::pictureRect() const {
  if (frame_width_px_ <= 0 || frame_height_px_ <= 0) return {};
  QSizeF size(frame_width_px_, frame_height_px_);
  size.scale(QSizeF(width(), height()), Qt::KeepAspectRatio);
  return {(width() - size.width()) / 2.0, (height() - size.height()) / 2.0, size.width(),
          size.height()};
}

QPointF VideoView::sliceCentre(unsigned index) const {
  const QRectF band = SliceBand(index, overlay_.slice_count(), frame_width_px_, frame_height_px_);
  if (band.isNull()) return {};
  const QRectF picture = pictureRect();
  const double scale = picture.width() / frame_width_px_;
  return picture.topLeft() + band.center() * scale;
}

void VideoView::paintEvent(QPaintEvent* /*event*/) {
  QPainter painter(this);
  painter.fillRect(rect(), QColor(24, 24, 28));
  if (image_.isNull()) {
    painter.setPen(QColor(200, 200, 200));
    QFont font = painter.font();
    font.setPointSizeF(font.pointSizeF() * 1.6);
    painter.setFont(font);
    painter.drawText(rect(), Qt::AlignCenter, stale_ ? staleText() : tr("No video"));
    return;
  }
  const QRectF picture = pictureRect();
  painter.setRenderHint(QPainter::SmoothPixmapTransform);
  painter.drawImage(picture, image_);

  // From here on, draw in camera-frame pixels.
  const double scale = picture.width() / frame_width_px_;
  painter.translate(picture.topLeft());
  painter.scale(scale, scale);
  painter.setRenderHint(QPainter::Antialiasing);
  const double line = 1.5 / scale;  // [frame px] a 1.5 px line on screen
  const unsigned slices = overlay_.slice_count();

  if (options_.chosen_slice && overlay_.chosen_slice() > 0) {
    const QRectF band =
        SliceBand(overlay_.chosen_slice(), slices, frame_width_px_, frame_height_px_);
    painter.fillRect(band, QColor(255, 200, 0, 55));
    painter.setPen(QPen(QColor(255, 200, 0), 2 * line));
    painter.drawRect(band);
  }
  if (options_.slice_grid && slices > 1) {
    painter.setPen(QPen(QColor(255, 255, 255, 120), line, Qt::DashLine));
    for (unsigned i = 1; i < slices; ++i) {
      const double y = frame_height_px_ * i / slices;
      painter.drawLine(QPointF(0, y), QPointF(frame_width_px_, y));
    }
    QFont font = painter.font();
    font.setPixelSize(static_cast<int>(std::max(10.0, 14.0 / scale)));
    font.setBold(true);
    painter.setFont(font);
    for (unsigned i = 1; i <= slices; ++i) {
      const QRectF band = SliceBand(i, slices, frame_width_px_, frame_height_px_);
      const QRectF tag(band.left() + 4 / scale, band.top() + 2 / scale, 22 / scale,
                       std::min(band.height() - 4 / scale, 18 / scale));
      painter.fillRect(tag, QColor(0, 0, 0, 140));
      painter.setPen(Qt::white);
      painter.drawText(tag, Qt::AlignCenter, QString::number(i));
    }
  }
  if (options_.reference_patch && overlay_.has_reference_patch()) {
    painter.setPen(QPen(QColor(80, 200, 255), 2 * line, Qt::DashLine));
    painter.drawRect(ToRectF(overlay_.reference_patch()));
  }
  if (options_.current_match && overlay_.has_match() && overlay_.has_current_match()) {
    painter.setPen(QPen(QColor(60, 230, 90), 2 * line));
    painter.drawRect(ToRectF(overlay_.current_match()));
  }
  if (options_.crosshair) {
    const QPointF centre(frame_width_px_ / 2.0, frame_height_px_ / 2.0);
    const double arm = std::min(frame_width_px_, frame_height_px_) / 12.0;
    painter.setPen(QPen(QColor(255, 70, 70), 1.5 * line));
    painter.drawLine(centre - QPointF(arm, 0), centre + QPointF(arm, 0));
    painter.drawLine(centre - QPointF(0, arm), centre + QPointF(0, arm));
    painter.drawEllipse(centre, arm / 3, arm / 3);
  }
  if (stale_) paintStale(painter, picture);
}

void VideoView::paintStale(QPainter& painter, const QRectF& picture) {
  // Over everything, in widget pixels: the picture is dimmed and a red band says how old it is.
  painter.resetTransform();
  painter.fillRect(picture, QColor(0, 0, 0, 120));
  painter.setPen(QPen(QColor(179, 38, 30), 6));
  painter.drawRect(picture.adjusted(3, 3, -3, -3));
  QFont font = painter.font();
  font.setBold(true);
  font.setPixelSize(std::max(16, static_cast<int>(picture.height() / 14)));
  painter.setFont(font);
  const QRectF band(picture.left(), picture.center().y() - font.pixelSize(), picture.width(),
                    2.0 * font.pixelSize());
  painter.fillRect(band, QColor(179, 38, 30, 220));
  painter.setPen(Qt::white);
  painter.drawText(band, Qt::AlignCenter, staleText());
}

void VideoView::mousePressEvent(QMouseEvent* event) {
  const QRectF picture = pictureRect();
  if (event->button() != Qt::LeftButton || picture.isEmpty() ||
      !picture.contains(event->position())) {
    QWidget::mousePressEvent(event);
    return;
  }
  const double y_px = (event->position().y() - picture.top()) * frame_height_px_ / picture.height();
  const unsigned index = SliceAt(y_px, frame_height_px_, overlay_.slice_count());
  if (index > 0) emit sliceClicked(index);
}

}  // namespace kapfix::station
