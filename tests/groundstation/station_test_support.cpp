#include "tests/groundstation/station_test_support.hpp"

#include <QBuffer>
#include <QImage>
#include <cmath>

namespace kapfix::station::testing {

bool WaitUntil(const std::function<bool()>& done, std::chrono::milliseconds wait) {
  QElapsedTimer timer;
  timer.start();
  while (!done()) {
    if (timer.elapsed() > wait.count()) return done();
    QCoreApplication::processEvents(QEventLoop::AllEvents, 20);
    QTest::qWait(5);
  }
  return true;
}

void ProcessEvents() {
  for (int i = 0; i < 5; ++i) QCoreApplication::processEvents();
}

kapfix::v1::Telemetry MakeTelemetry(std::uint64_t frame, int x_px, int y_px,
                                    std::int64_t capture_time_us) {
  kapfix::v1::Telemetry telemetry;
  telemetry.set_frame_number(frame);
  telemetry.mutable_displacement()->set_x_px(x_px);
  telemetry.mutable_displacement()->set_y_px(y_px);
  telemetry.set_confidence(0.75F);
  telemetry.set_distance(1234);
  telemetry.set_pan_angle_deg(1.5F);
  telemetry.set_tilt_angle_deg(-0.5F);
  telemetry.set_fps(29.5F);
  telemetry.set_mode(kapfix::v1::MODE_FIXATE);
  telemetry.set_slice(4);
  telemetry.mutable_header()->set_capture_time_us(capture_time_us);
  return telemetry;
}

kapfix::v1::SliceReport MakeSliceReport(unsigned slices, unsigned recommended) {
  kapfix::v1::SliceReport report;
  for (unsigned i = 1; i <= slices; ++i) {
    auto* slice = report.add_slices();
    slice->set_index(i);
    slice->set_dc(i == recommended ? 21 : 100 + i);
    slice->set_fft(1000.0 * i);
    slice->set_rank(i == recommended ? 1 : 0);
    for (int t = 0; t < 40; ++t)
      slice->add_graph_px(static_cast<float>(10.0 * std::sin(t * 0.3 * i)));
  }
  report.set_recommended_slice(recommended);
  report.set_progress_done(40);
  report.set_progress_total(40);
  report.set_finished(true);
  return report;
}

kapfix::v1::VideoFrame MakeVideoFrame(int width, int height, unsigned slices) {
  QImage image(width, height, QImage::Format_RGB32);
  image.fill(QColor(90, 120, 90));
  QByteArray jpeg;
  QBuffer buffer(&jpeg);
  buffer.open(QIODevice::WriteOnly);
  image.save(&buffer, "JPEG", 80);
  kapfix::v1::VideoFrame frame;
  frame.set_jpeg(jpeg.toStdString());
  frame.set_width_px(static_cast<std::uint32_t>(width));
  frame.set_height_px(static_cast<std::uint32_t>(height));
  frame.set_frame_width_px(static_cast<std::uint32_t>(width));
  frame.set_frame_height_px(static_cast<std::uint32_t>(height));
  frame.set_frame_number(7);
  frame.mutable_overlay()->set_slice_count(slices);
  frame.mutable_overlay()->set_chosen_slice(2);
  return frame;
}

}  // namespace kapfix::station::testing
