// The Aravis backend of a build without aravis-0.8 (pkg-config did not find libaravis-dev,
// or libusb-1.0-0-dev which its .pc file needs; SPEC §8). Every call fails with that reason,
// so a configuration asking for a GenICam camera gets a clear error rather than a link error.
#include "agent/capture/aravis_frame_source.hpp"

namespace kapfix::agent {

struct AravisFrameSource::Impl {
  AravisFrameSourceOptions options;
};

namespace {

bool BuiltWithout(const std::string& id, std::string* error) {
  if (error) {
    *error = "Aravis camera '" + (id.empty() ? std::string("(first)") : id) +
             "': kapfix was built without Aravis (install libaravis-dev and libusb-1.0-0-dev, "
             "then configure again)";
  }
  return false;
}

}  // namespace

AravisFrameSource::AravisFrameSource(AravisFrameSourceOptions options)
    : impl_(std::make_unique<Impl>(Impl{std::move(options)})) {}
AravisFrameSource::~AravisFrameSource() = default;

bool AravisFrameSource::Available() { return false; }

bool AravisFrameSource::Open(std::string* error) {
  return BuiltWithout(impl_->options.camera_id, error);
}
bool AravisFrameSource::Grab(CapturedFrame* /*frame*/, std::string* error) {
  return BuiltWithout(impl_->options.camera_id, error);
}
bool AravisFrameSource::Apply(const kapfix::v1::CameraSettings& /*settings*/, std::string* error) {
  return BuiltWithout(impl_->options.camera_id, error);
}
std::string AravisFrameSource::Describe() const { return "aravis (built without Aravis)"; }

}  // namespace kapfix::agent
