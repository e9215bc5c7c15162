#pragma once

// Shared by the station's tests: waiting on the Qt event loop with a bound, and messages as
// the agent would send them.

#include <QCoreApplication>
#include <QElapsedTimer>
#include <QTest>
#include <chrono>
#include <functional>

#include "kapfix/v1/slices.pb.h"
#include "kapfix/v1/telemetry.pb.h"
#include "kapfix/v1/video.pb.h"

namespace kapfix::station::testing {

// Every wait is bounded by this: a failing test fails, it does not hang.
inline constexpr auto kWait = std::chrono::milliseconds(4000);

// Runs the event loop until `done` holds or `wait` passed; returns `done()`.
bool WaitUntil(const std::function<bool()>& done, std::chrono::milliseconds wait = kWait);

// Runs the event loop for queued calls (replies of the fake arrive queued).
void ProcessEvents();

kapfix::v1::Telemetry MakeTelemetry(std::uint64_t frame, int x_px, int y_px,
                                    std::int64_t capture_time_us);

// A finished report over `slices` slices recommending `recommended`, with graphs.
kapfix::v1::SliceReport MakeSliceReport(unsigned slices, unsigned recommended);

// A grey JPEG of w×h with an overlay of `slices` slices.
kapfix::v1::VideoFrame MakeVideoFrame(int width, int height, unsigned slices);

}  // namespace kapfix::station::testing
