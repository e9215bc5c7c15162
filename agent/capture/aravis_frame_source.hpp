#pragma once

#include <memory>
#include <string>

#include "agent/capture/frame_source.hpp"

namespace kapfix::agent {

struct AravisFrameSourceOptions {
  std::string camera_id;       // Aravis device id ("" = the first camera found; `arv-tool-0.8`)
  int width = 0;               // [px] region of interest from the sensor's top left; 0 = as set
  int height = 0;              // [px]
  double fps = 0;              // [frames/s] 0 = leave the camera's frame rate
  std::string pixel_format;    // "" = as set, else a GenICam name: Mono8, BayerRG8, RGB8 …
  int grab_timeout_ms = 1000;  // [ms] Grab reports a lost camera after this long without a frame
  int buffers = 4;             // frames queued in the stream
  // Aravis's built-in simulated GenICam camera (the "Fake" interface, id "Fake_1") is
  // enabled: lets tests run this backend's whole path without hardware.
  bool enable_fake_camera = false;

  bool IsValid(std::string* error) const;
};

// A GenICam camera (USB3 Vision or GigE Vision; IDS uEye class) through the Aravis C API
// (Debian's libaravis-dev, aravis-0.8).
//
// Frames arrive as Mono8, Bayer??8, RGB8 or BGR8 and are converted to BGR. The camera settings
// use GenICam's features: gain [dB] Gain, exposure [µs] ExposureTime (their auto modes turned
// off; both checked against the camera's bounds), automatic exposure ExposureAuto
// (Continuous / Off). Incomplete frames (GigE packet loss) are skipped; Grab fails
// only when no complete frame arrives within grab_timeout_ms.
//
// Aravis (and the glib headers it brings, whose `signals` clashes with Qt) stays inside the
// .cpp (SPEC §8): this header is safe to include anywhere. When CMake did not find aravis-0.8
// the build uses a stub whose Open fails with "built without Aravis".
class AravisFrameSource : public FrameSource {
 public:
  explicit AravisFrameSource(AravisFrameSourceOptions options);
  ~AravisFrameSource() override;
  AravisFrameSource(const AravisFrameSource&) = delete;
  AravisFrameSource& operator=(const AravisFrameSource&) = delete;

  bool Open(std::string* error) override;
  bool Grab(CapturedFrame* frame, std::string* error) override;
  // Fails "not open" before Open.
  bool Apply(const kapfix::v1::CameraSettings& settings, std::string* error) override;
  std::string Describe() const override;

  // False in a build without Aravis (the stub).
  static bool Available();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace kapfix::agent
