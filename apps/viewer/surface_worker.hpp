// The paste's surface (dentsph/surface.hpp) built beside the frames: the render loop hands the
// worker the newest paste positions and draws the newest finished mesh, so a surface that takes
// longer than a frame to build never holds a frame back (docs/viewer.md).
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#include <tbb/task_arena.h>

#include "dentsph/surface.hpp"

namespace dentsph::viewer {

class SurfaceWorker {
 public:
  explicit SurfaceWorker(real spacing);
  ~SurfaceWorker();  // stops the worker and waits for it
  SurfaceWorker(const SurfaceWorker&) = delete;
  SurfaceWorker& operator=(const SurfaceWorker&) = delete;

  // The paste's positions (m) to build next, replacing any not yet started; returns its number
  // (1, 2, ... in the order submitted).
  std::uint64_t submit(const std::vector<Vec3>& points);
  // Moves the newest finished surface into `mesh` when it was submitted as number `oldest` or later
  // (a surface of paste from before a reset is not shown); false otherwise.
  bool take(SurfaceMesh& mesh, std::uint64_t oldest = 0);
  // Waits until the surface of paste number `number` (or a newer one) is finished, at most
  // `timeout`; whether it was.
  bool wait_for(std::uint64_t number, std::chrono::milliseconds timeout);
  // The surfaces built so far (a paste replaced before its build started is not).
  std::uint64_t built();

 private:
  void run();
  const real spacing_;
  std::mutex m_;
  std::condition_variable cv_;       // a paste to build, or stop
  std::condition_variable done_cv_;  // a surface finished
  std::vector<Vec3> pending_;
  bool has_pending_ = false, stop_ = false;
  std::uint64_t submitted_ = 0, pending_number_ = 0, done_number_ = 0;
  SurfaceMesh done_;
  bool has_done_ = false;
  std::uint64_t built_ = 0;
  tbb::task_arena arena_{1};
  std::thread thread_;  // last: started once the rest is ready
};

}  // namespace dentsph::viewer
