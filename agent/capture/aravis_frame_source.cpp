// The only translation unit that includes Aravis and glib (SPEC §8: glib's `signals` member
// clashes with Qt's keyword, so these headers must not leak into any header).
#include "agent/capture/aravis_frame_source.hpp"

#include <arv.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "agent/capture/camera_setting_controls.hpp"
#include "common/time/steady_clock.hpp"

namespace kapfix::agent {
namespace {

// Takes a GError's message and frees it; "" when there was no error.
std::string TakeError(GError** error) {
  if (*error == nullptr) return "";
  std::string message = (*error)->message ? (*error)->message : "unknown Aravis error";
  g_clear_error(error);
  return message;
}

// GenICam Bayer names give the colour of the top-left pixel pair (RG: R at (0,0), G at
// (1,0)); OpenCV's constants name the pair at (1,1), one row and column further.
bool BayerCode(ArvPixelFormat format, int* code) {
  if (format == ARV_PIXEL_FORMAT_BAYER_RG_8)
    *code = cv::COLOR_BayerBG2BGR;
  else if (format == ARV_PIXEL_FORMAT_BAYER_GR_8)
    *code = cv::COLOR_BayerGB2BGR;
  else if (format == ARV_PIXEL_FORMAT_BAYER_GB_8)
    *code = cv::COLOR_BayerGR2BGR;
  else if (format == ARV_PIXEL_FORMAT_BAYER_BG_8)
    *code = cv::COLOR_BayerRG2BGR;
  else
    return false;
  return true;
}

}  // namespace

struct AravisFrameSource::Impl {
  AravisFrameSourceOptions options;
  ArvCamera* camera = nullptr;
  ArvStream* stream = nullptr;
  std::string id;  // the device id once open
  std::uint64_t next_index = 0;
  CameraSettingControls controls;  // the settings this backend applies (made in the constructor)

  std::string Name() const {
    const std::string& shown = id.empty() ? options.camera_id : id;
    return "Aravis camera '" + (shown.empty() ? std::string("(first)") : shown) + "'";
  }
  bool Fail(const std::string& reason, std::string* error) const {
    if (error) *error = Name() + ": " + reason;
    return false;
  }
  void Close() {
    if (camera != nullptr && stream != nullptr) arv_camera_stop_acquisition(camera, nullptr);
    if (stream != nullptr) g_object_unref(stream);
    if (camera != nullptr) g_object_unref(camera);
    stream = nullptr;
    camera = nullptr;
  }
  // Finds the camera (options.camera_id, or the first one) and opens it; sets `id`.
  bool Connect(std::string* error) {
    arv_update_device_list();
    if (arv_get_n_devices() == 0) {
      return Fail(
          "no GenICam camera found (USB3 Vision or GigE Vision; check the cable, udev "
          "permissions and `arv-tool-0.8`)",
          error);
    }
    GError* gerror = nullptr;
    camera =
        arv_camera_new(options.camera_id.empty() ? nullptr : options.camera_id.c_str(), &gerror);
    if (camera == nullptr) {
      const std::string reason = TakeError(&gerror);
      std::string found;
      for (unsigned i = 0; i < arv_get_n_devices() && i < 8; ++i) {
        found += (i ? ", " : "") + std::string(arv_get_device_id(i));
      }
      return Fail("cannot open (" + reason + "); cameras found: " + found, error);
    }
    // arv_camera_new(nullptr) opens the first device of the list.
    if (options.camera_id.empty()) {
      const char* first = arv_get_device_id(0);
      id = first ? first : "";
    } else {
      id = options.camera_id;
    }
    return true;
  }
  // Closes the camera and fails with `what` and the GError's message.
  bool CloseAndFail(const std::string& what, GError** gerror, std::string* error) {
    const std::string reason = TakeError(gerror);
    Close();
    return Fail(what + " (" + reason + ")", error);
  }
  // Each setting is applied in the order GenICam cameras expect: format and region first
  // (they change the payload size), then the frame rate they allow.
  bool ApplySettings(std::string* error) {
    GError* gerror = nullptr;
    if (!options.pixel_format.empty()) {
      arv_camera_set_pixel_format_from_string(camera, options.pixel_format.c_str(), &gerror);
      if (gerror)
        return CloseAndFail("cannot set pixel format " + options.pixel_format, &gerror, error);
    }
    if (options.width > 0) {
      arv_camera_set_region(camera, 0, 0, options.width, options.height, &gerror);
      if (gerror) {
        return CloseAndFail("cannot set region " + std::to_string(options.width) + "x" +
                                std::to_string(options.height),
                            &gerror, error);
      }
    }
    if (options.fps > 0) {
      arv_camera_set_frame_rate(camera, options.fps, &gerror);
      if (gerror) {
        return CloseAndFail("cannot set frame rate " + fmt::format("{:g}", options.fps), &gerror,
                            error);
      }
    }
    return true;
  }
  // Creates the stream with options.buffers buffers and starts continuous acquisition.
  bool StartStream(std::string* error) {
    GError* gerror = nullptr;
    if (arv_camera_is_gv_device(camera)) {
      arv_camera_gv_auto_packet_size(camera, &gerror);  // best effort: jumbo frames if the
      TakeError(&gerror);                               // network allows them
    }
    stream = arv_camera_create_stream(camera, nullptr, nullptr, &gerror);
    if (stream == nullptr) return CloseAndFail("cannot create a stream", &gerror, error);
    const guint payload = arv_camera_get_payload(camera, &gerror);
    if (gerror || payload == 0) {
      return CloseAndFail("cannot read the payload size", &gerror, error);
    }
    for (int i = 0; i < options.buffers; ++i) {
      arv_stream_push_buffer(stream, arv_buffer_new(payload, nullptr));
    }
    arv_camera_set_acquisition_mode(camera, ARV_ACQUISITION_MODE_CONTINUOUS, &gerror);
    TakeError(&gerror);  // some cameras fix the mode; continuous is their default anyway
    arv_camera_start_acquisition(camera, &gerror);
    if (gerror) return CloseAndFail("cannot start acquisition", &gerror, error);
    return true;
  }
  // [dB] GenICam's Gain, GainAuto turned off first; checked against the camera's bounds.
  bool SetGain(double db, std::string* reason) const {
    if (!std::isfinite(db)) return Refuse("not a finite number", reason);
    GError* gerror = nullptr;
    if (!arv_camera_is_gain_available(camera, &gerror)) {
      return Refuse("the camera has no Gain feature", &gerror, reason);
    }
    if (arv_camera_is_gain_auto_available(camera, nullptr)) {
      arv_camera_set_gain_auto(camera, ARV_AUTO_OFF, &gerror);
      TakeError(&gerror);  // a camera without GainAuto is already manual
    }
    double low = 0;
    double high = 0;
    arv_camera_get_gain_bounds(camera, &low, &high, &gerror);
    if (!gerror && (db < low || db > high)) {
      return Refuse(fmt::format("outside its range [{:g}, {:g}] dB", low, high), reason);
    }
    TakeError(&gerror);
    arv_camera_set_gain(camera, db, &gerror);
    if (gerror) return Refuse("cannot set it", &gerror, reason);
    return true;
  }
  // [µs] GenICam's ExposureTime, ExposureAuto turned off first; checked against its bounds.
  bool SetExposure(double us, std::string* reason) const {
    if (!std::isfinite(us) || us <= 0) return Refuse("must be > 0 µs", reason);
    GError* gerror = nullptr;
    if (!arv_camera_is_exposure_time_available(camera, &gerror)) {
      return Refuse("the camera has no ExposureTime feature", &gerror, reason);
    }
    if (arv_camera_is_exposure_auto_available(camera, nullptr)) {
      arv_camera_set_exposure_time_auto(camera, ARV_AUTO_OFF, &gerror);
      TakeError(&gerror);
    }
    double low = 0;
    double high = 0;
    arv_camera_get_exposure_time_bounds(camera, &low, &high, &gerror);
    if (!gerror && (us < low || us > high)) {
      return Refuse(fmt::format("outside its range [{:g}, {:g}] µs", low, high), reason);
    }
    TakeError(&gerror);
    arv_camera_set_exposure_time(camera, us, &gerror);
    if (gerror) return Refuse("cannot set it", &gerror, reason);
    return true;
  }
  // GenICam's ExposureAuto: Continuous when on, Off when off (a camera without the feature is
  // always manual, so off needs nothing).
  bool SetAutoExposure(bool on, std::string* reason) const {
    GError* gerror = nullptr;
    if (!arv_camera_is_exposure_auto_available(camera, &gerror)) {
      if (!on) return true;
      return Refuse("the camera has no ExposureAuto feature", &gerror, reason);
    }
    arv_camera_set_exposure_time_auto(camera, on ? ARV_AUTO_CONTINUOUS : ARV_AUTO_OFF, &gerror);
    if (gerror) return Refuse("cannot set ExposureAuto", &gerror, reason);
    return true;
  }
  static bool Refuse(const std::string& what, std::string* reason) {
    if (reason) *reason = what;
    return false;
  }
  // `what`, with the GError's message when there is one.
  static bool Refuse(const std::string& what, GError** gerror, std::string* reason) {
    const std::string detail = TakeError(gerror);
    return Refuse(detail.empty() ? what : what + " (" + detail + ")", reason);
  }
  // Converts one complete buffer; false + reason for a pixel format we do not read.
  bool Convert(ArvBuffer* buffer, cv::Mat* bgr, std::string* reason) const {
    const int width = arv_buffer_get_image_width(buffer);
    const int height = arv_buffer_get_image_height(buffer);
    const ArvPixelFormat format = arv_buffer_get_image_pixel_format(buffer);
    std::size_t size = 0;
    const void* data = arv_buffer_get_image_data(buffer, &size);
    const int channels =
        format == ARV_PIXEL_FORMAT_RGB_8_PACKED || format == ARV_PIXEL_FORMAT_BGR_8_PACKED ? 3 : 1;
    if (data == nullptr || width <= 0 || height <= 0 ||
        size < static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * channels) {
      *reason = "frame shorter than its size";
      return false;
    }
    // A header over Aravis's buffer; the conversions below write a new Mat, so the buffer can
    // go back to the stream right after.
    const cv::Mat raw(height, width, channels == 3 ? CV_8UC3 : CV_8UC1, const_cast<void*>(data));
    int bayer = 0;
    if (format == ARV_PIXEL_FORMAT_MONO_8) {
      cv::cvtColor(raw, *bgr, cv::COLOR_GRAY2BGR);
    } else if (BayerCode(format, &bayer)) {
      cv::cvtColor(raw, *bgr, bayer);
    } else if (format == ARV_PIXEL_FORMAT_RGB_8_PACKED) {
      cv::cvtColor(raw, *bgr, cv::COLOR_RGB2BGR);
    } else if (format == ARV_PIXEL_FORMAT_BGR_8_PACKED) {
      *bgr = raw.clone();
    } else {
      const char* name = arv_camera_get_pixel_format_as_string(camera, nullptr);
      *reason = fmt::format(
          "unsupported pixel format 0x{:08x} ({}); set the format to Mono8, "
          "BayerRG8, BayerGR8, BayerGB8, BayerBG8, RGB8 or BGR8",
          format, name ? name : "?");
      return false;
    }
    return true;
  }
};

AravisFrameSource::AravisFrameSource(AravisFrameSourceOptions options)
    : impl_(std::make_unique<Impl>()) {
  impl_->options = std::move(options);
  const Impl* d = impl_.get();
  using kapfix::v1::CameraSettings;
  impl_->controls
      .Add(CameraSettings::kGainDbFieldNumber,
           [d](double db, std::string* reason) { return d->SetGain(db, reason); })
      .Add(CameraSettings::kExposureUsFieldNumber,
           [d](double us, std::string* reason) { return d->SetExposure(us, reason); })
      .Add(CameraSettings::kAutoExposureFieldNumber,
           [d](double on, std::string* reason) { return d->SetAutoExposure(on != 0, reason); });
}

AravisFrameSource::~AravisFrameSource() { impl_->Close(); }

bool AravisFrameSource::Available() { return true; }

bool AravisFrameSource::Open(std::string* error) {
  Impl& d = *impl_;
  d.Close();
  d.id.clear();
  d.next_index = 0;
  std::string reason;
  if (!d.options.IsValid(&reason)) return d.Fail(reason, error);
  if (d.options.enable_fake_camera) arv_enable_interface("Fake");
  if (!d.Connect(error) || !d.ApplySettings(error) || !d.StartStream(error)) return false;
  spdlog::info("camera: {} open", Describe());
  return true;
}

bool AravisFrameSource::Grab(CapturedFrame* frame, std::string* error) {
  Impl& d = *impl_;
  if (d.stream == nullptr) return d.Fail("not open", error);
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::milliseconds(d.options.grab_timeout_ms);
  int incomplete = 0;
  while (true) {
    const auto left = std::chrono::duration_cast<std::chrono::microseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) break;
    ArvBuffer* buffer = arv_stream_timeout_pop_buffer(d.stream, static_cast<guint64>(left.count()));
    if (buffer == nullptr) break;
    if (arv_buffer_get_status(buffer) != ARV_BUFFER_STATUS_SUCCESS) {
      ++incomplete;
      arv_stream_push_buffer(d.stream, buffer);
      continue;
    }
    const std::int64_t now = SteadyClockNowUs();
    std::string reason;
    const bool converted = d.Convert(buffer, &frame->image, &reason);
    arv_stream_push_buffer(d.stream, buffer);
    if (!converted) return d.Fail(reason, error);
    frame->capture_time_us = now;
    frame->index = d.next_index++;
    return true;
  }
  return d.Fail("lost (no complete frame within " + std::to_string(d.options.grab_timeout_ms) +
                    " ms, " + std::to_string(incomplete) + " incomplete)",
                error);
}

bool AravisFrameSource::Apply(const kapfix::v1::CameraSettings& settings, std::string* error) {
  Impl& d = *impl_;
  if (d.camera == nullptr) return d.Fail("not open", error);
  return d.controls.Apply(settings, d.Name(), error);
}

std::string AravisFrameSource::Describe() const {
  const Impl& d = *impl_;
  std::string text =
      "aravis " + (d.id.empty() ? (d.options.camera_id.empty() ? std::string("(first camera)")
                                                               : d.options.camera_id)
                                : d.id);
  if (d.camera != nullptr) {
    const char* vendor = arv_camera_get_vendor_name(d.camera, nullptr);
    const char* model = arv_camera_get_model_name(d.camera, nullptr);
    const char* serial = arv_camera_get_device_serial_number(d.camera, nullptr);
    text += fmt::format(" ({} {}, serial {})", vendor ? vendor : "?", model ? model : "?",
                        serial ? serial : "?");
  }
  return text;
}

}  // namespace kapfix::agent
