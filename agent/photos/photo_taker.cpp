#include "agent/photos/photo_taker.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>

#include "agent/photos/photo_quality.hpp"

namespace kapfix::agent {
namespace {

// Photos queued for the disk at most; beyond this the disk is too slow and a photo is refused
// (logged) rather than memory growing.
constexpr std::size_t kMaxQueuedPhotos = 8;
// About 3 bytes per pixel is more than a JPEG at quality 95 ever needs; the store keeps room
// for twice this free.
constexpr std::uintmax_t kRoughPhotoBytes = std::uintmax_t{3} * 1024 * 1024;
// Saved photos whose metadata is kept for the flight's figures (a few hundred bytes each);
// beyond, the figures are those of the first ones.
constexpr std::size_t kMaxRememberedPhotos = 100000;

std::int64_t WallClockUs() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace

PhotoTaker::PhotoTaker(PhotoStore& store, StreamSink& sink, std::function<std::string()> lens)
    : store_(store), sink_(sink), lens_(std::move(lens)), thread_([this] { WriterThread(); }) {}

PhotoTaker::~PhotoTaker() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

bool PhotoTaker::Request(const std::string& note, std::string* error, std::string* file_name) {
  if (!store_.CheckWritable(kRoughPhotoBytes, error)) return false;
  std::lock_guard lock(mutex_);
  if (jobs_.size() + requested_.size() + waiting_.size() >= kMaxQueuedPhotos) {
    if (error) {
      *error =
          "photo refused: " + std::to_string(jobs_.size() + requested_.size() + waiting_.size()) +
          " photos still being taken or written";
    }
    return false;
  }
  requested_.push_back(Requested{note, store_.NewFileName(WallClockUs())});
  if (file_name) *file_name = requested_.back().file_name;
  return true;
}

void PhotoTaker::SetSettings(const kapfix::v1::PhotoSettings& photo) {
  shutter_.Set(photo);
  cameras_.Select(photo.camera());
  std::lock_guard lock(mutex_);
  interval_s_ = photo.interval_s();  // [s] 0 = off
}

void PhotoTaker::Flush() {
  std::unique_lock lock(mutex_);
  drained_.wait(lock, [this] { return jobs_.empty() && !writing_; });
}

std::vector<kapfix::v1::PhotoMetadata> PhotoTaker::Saved() const {
  std::lock_guard lock(mutex_);
  return saved_metadata_;
}

std::vector<std::string> PhotoTaker::Resend(std::int64_t since_us) {
  std::vector<kapfix::v1::PhotoMetadata> photos = store_.ListSince(since_us);
  std::vector<std::string> names;
  names.reserve(photos.size());
  for (const auto& metadata : photos) names.push_back(metadata.file_name());
  if (photos.empty()) return names;
  {
    std::lock_guard lock(mutex_);
    jobs_.push_back(Job{cv::Mat(), {}, std::move(photos), {}});
  }
  wake_.notify_one();
  return names;
}

void PhotoTaker::OnStep(const CapturedFrame& frame, const FrameOutcome& outcome,
                        const TelemetryRecord& record) {
  std::vector<Requested> photos;
  {
    std::lock_guard lock(mutex_);
    std::swap(photos, requested_);
    if (photos.empty() && interval_s_ > 0) {
      const auto period_us = static_cast<std::int64_t>(std::llround(interval_s_ * 1e6));
      if (!last_auto_us_ || frame.capture_time_us - *last_auto_us_ >= period_us) {
        if (last_auto_us_) photos.push_back({"every " + std::to_string(interval_s_) + " s", ""});
        last_auto_us_ = frame.capture_time_us;
      }
    }
    // The requests wait for the shutter, which sees every frame.
    if (!photos.empty()) shutter_.Request();
    for (Requested& photo : photos) waiting_.push_back(std::move(photo));
    photos.clear();
  }
  const std::optional<ShutterShot> shot = shutter_.OnStep(frame, record);
  if (!shot) return;
  {
    std::lock_guard lock(mutex_);
    std::swap(photos, waiting_);
    if (photos.empty()) return;
    // Requests were bounded with the queue when made; only interval photos can overflow it.
    if (jobs_.size() + photos.size() > kMaxQueuedPhotos && photos.front().file_name.empty()) {
      ++failed_;
      spdlog::error("photo of frame {} dropped: the disk is not keeping up", frame.index);
      return;
    }
  }
  kapfix::v1::PhotoMetadata metadata;
  metadata.set_capture_time_us(WallClockUs());
  auto* d = metadata.mutable_displacement();
  d->set_x_px(static_cast<std::int32_t>(std::lround(record.displacement_x_px)));
  d->set_y_px(static_cast<std::int32_t>(std::lround(record.displacement_y_px)));
  d->set_x_subpx(
      static_cast<float>(record.displacement_x_px - std::round(record.displacement_x_px)));
  d->set_y_subpx(
      static_cast<float>(record.displacement_y_px - std::round(record.displacement_y_px)));
  metadata.set_pan_angle_deg(static_cast<float>(record.angle_pan_deg));
  metadata.set_tilt_angle_deg(static_cast<float>(record.angle_tilt_deg));
  metadata.set_slice(static_cast<std::uint32_t>(record.slice));
  metadata.set_lens_profile(lens_ ? lens_() : std::string());
  metadata.set_confidence(static_cast<float>(record.confidence));
  FillShotQuality(*shot, &metadata);
  const cv::Rect patch =
      PatchInFrame(outcome.patch, {record.displacement_x_px, record.displacement_y_px});
  // cv::Mat copies share one pixel buffer: one clone for all photos of this frame.
  const cv::Mat image = frame.image.clone();
  {
    std::lock_guard lock(mutex_);
    for (Requested& photo : photos) {
      Job job{image, metadata, {}, patch};
      job.metadata.set_note(std::move(photo.note));
      job.metadata.set_file_name(std::move(photo.file_name));
      jobs_.push_back(std::move(job));
    }
  }
  wake_.notify_one();
}

std::vector<kapfix::v1::Photo> PhotoTaker::Chunks(const kapfix::v1::PhotoMetadata& metadata,
                                                  const std::string& bytes) {
  std::vector<kapfix::v1::Photo> chunks;
  std::size_t offset = 0;
  do {
    const std::size_t size = std::min(kChunkBytes, bytes.size() - offset);
    kapfix::v1::Photo photo;
    photo.mutable_header()->set_capture_time_us(metadata.capture_time_us());
    *photo.mutable_metadata() = metadata;
    photo.set_data(bytes.substr(offset, size));
    photo.set_offset_bytes(offset);
    photo.set_total_bytes(bytes.size());
    chunks.push_back(std::move(photo));
    offset += size;
  } while (offset < bytes.size());
  return chunks;
}

void PhotoTaker::Offer(const kapfix::v1::PhotoMetadata& metadata, const std::string& bytes) {
  for (const kapfix::v1::Photo& chunk : Chunks(metadata, bytes)) {
    if (!sink_.Publish(chunk)) {
      spdlog::warn("photo {} not sent now (link queue full); it stays on disk",
                   metadata.file_name());
      return;
    }
  }
}

void PhotoTaker::WriterThread() {
  std::unique_lock lock(mutex_);
  while (true) {
    writing_ = false;
    drained_.notify_all();
    wake_.wait(lock, [this] { return stop_ || !jobs_.empty(); });
    if (jobs_.empty()) return;  // stopping, nothing left to write
    Job job = std::move(jobs_.front());
    jobs_.pop_front();
    writing_ = true;
    lock.unlock();
    if (job.image.empty()) {
      for (const auto& metadata : job.resend) {
        try {
          Offer(metadata, store_.ReadFile(metadata.file_name()));
        } catch (const std::exception& e) {
          spdlog::warn("photo {} not resent: {}", metadata.file_name(), e.what());
        }
      }
    } else {
      std::string why;
      // The reserve again, here, for every photo: interval photos are not requested through
      // Request(), and the disk may have filled since.
      if (!store_.CheckWritable(kRoughPhotoBytes, &why)) {
        ++failed_;
        if (!reserve_refusal_logged_) spdlog::error("photo not saved: {}", why);
        reserve_refusal_logged_ = true;
        lock.lock();
        continue;
      }
      reserve_refusal_logged_ = false;
      try {
        FillSharpness(job.image, job.patch, &job.metadata);
        const PhotoRequest request{job.metadata.file_name(), job.metadata.note(), job.image};
        const TakenPhoto taken = cameras_.Take(request, &job.metadata);
        const kapfix::v1::PhotoMetadata saved = store_.SaveFile(taken.bytes, job.metadata);
        cameras_.Stored(taken);
        ++saved_;
        {
          std::lock_guard saved_lock(mutex_);
          if (saved_metadata_.size() < kMaxRememberedPhotos) saved_metadata_.push_back(saved);
        }
        spdlog::info("photo {} saved ({} KiB)", saved.file_name(), taken.bytes.size() / 1024);
        Offer(saved, taken.bytes);
      } catch (const std::exception& e) {
        ++failed_;
        spdlog::error("photo not saved: {}", e.what());
      }
    }
    lock.lock();
  }
}

}  // namespace kapfix::agent
