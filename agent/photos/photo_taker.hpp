#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "agent/photos/photo_cameras.hpp"
#include "agent/photos/photo_shutter.hpp"
#include "agent/photos/photo_store.hpp"
#include "agent/pipeline/step_observer.hpp"
#include "agent/server/stream_sink.hpp"

namespace kapfix::agent {

// Takes the stabilised photos (SPEC §4): on command, or every N seconds of camera time. The
// control thread only copies the frame; a writer thread stores it (PhotoStore: disk first),
// then offers it to the station as Photo chunks. Photos taken while the link is down stay on
// disk and are sent again on request (Resend). Each request is one photo, also several in one
// frame, stored with its note; interval photos keep the same free-space reserve as commanded
// ones (checked by the writer before each photo). When the photo is taken is the
// PhotoShutter's choice (issue 13: at once, or at the quietest moment of a window); the
// sidecar carries the shot's quality, and the writer adds the stored image's sharpness.
class PhotoTaker : public StepObserver {
 public:
  // [bytes] each Photo message carries at most this much of the file, well under the
  // station's receive limit.
  static constexpr std::size_t kChunkBytes = std::size_t{256} * 1024;

  // `lens` names the lens profile in use, read at each photo.
  PhotoTaker(PhotoStore& store, StreamSink& sink, std::function<std::string()> lens);
  ~PhotoTaker() override;  // joins the writer; queued photos are written first
  PhotoTaker(const PhotoTaker&) = delete;
  PhotoTaker& operator=(const PhotoTaker&) = delete;

  void OnStep(const CapturedFrame& frame, const FrameOutcome& outcome,
              const TelemetryRecord& record) override;

  // Any thread. A photo of the next frame, stored under the name returned in `file_name`
  // (optional) with `note`; false (and why) when the store cannot take one now.
  bool Request(const std::string& note, std::string* error, std::string* file_name = nullptr);
  // Any thread. Which camera takes the next photos (PhotoSettings.camera); a still camera
  // that cannot falls back to the agent's (PhotoCameras).
  void SetCamera(kapfix::v1::PhotoCamera camera) { cameras_.Select(camera); }
  void SetStillCamera(std::shared_ptr<PhotoTrigger> still) {
    cameras_.SetStillCamera(std::move(still));
  }
  // Any thread: shutter, window, cap, exposure, camera and the interval of automatic photos
  // from the next frame on (every field set, as AgentConfig::IsValid checks).
  void SetSettings(const kapfix::v1::PhotoSettings& photo);
  // Any thread: waits until every photo the shutter fired is written (or failed).
  void Flush();
  // Any thread: the metadata of the photos saved since the start (the first 100,000),
  // oldest first.
  std::vector<kapfix::v1::PhotoMetadata> Saved() const;
  // Publishes again every stored photo taken at or after `since_us`; returns their file
  // names, oldest first. They are listed now and sent by the writer thread, so the names are
  // what a station will get.
  std::vector<std::string> Resend(std::int64_t since_us);

  std::uint64_t saved() const { return saved_.load(); }
  std::uint64_t failed() const { return failed_.load(); }

  // The Photo messages of one file, in order.
  static std::vector<kapfix::v1::Photo> Chunks(const kapfix::v1::PhotoMetadata& metadata,
                                               const std::string& bytes);

 private:
  struct Job {
    cv::Mat image;  // empty: a resend
    kapfix::v1::PhotoMetadata metadata;
    std::vector<kapfix::v1::PhotoMetadata> resend;  // the stored photos to send again
    cv::Rect patch;  // [px] where the reference patch is seen in `image`; empty = none
  };
  void WriterThread();
  void Offer(const kapfix::v1::PhotoMetadata& metadata, const std::string& bytes);

  PhotoStore& store_;
  StreamSink& sink_;
  std::function<std::string()> lens_;
  PhotoCameras cameras_;  // used by the writer thread; thread-safe
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable drained_;  // jobs_ empty and the writer idle
  bool writing_ = false;             // the writer holds a job
  std::deque<Job> jobs_;
  bool stop_ = false;
  struct Requested {
    std::string note;
    std::string file_name;
  };
  std::vector<Requested> requested_;  // for the next frame; with jobs_, at most kMaxQueuedPhotos
  std::vector<Requested> waiting_;    // for the shutter's window (counted with requested_)
  std::vector<kapfix::v1::PhotoMetadata> saved_metadata_;
  PhotoShutter shutter_;                 // Set() from any thread, else the control thread's
  bool reserve_refusal_logged_ = false;  // writer thread: one line per disk-full episode
  double interval_s_ = 0;
  std::optional<std::int64_t> last_auto_us_;  // control thread only
  std::atomic<std::uint64_t> saved_{0};
  std::atomic<std::uint64_t> failed_{0};
  std::thread thread_;
};

}  // namespace kapfix::agent
