#include "surface_worker.hpp"

#include <exception>
#include <utility>

#include <pthread.h>

#include <tbb/task_arena.h>

namespace dentsph::viewer {

SurfaceWorker::SurfaceWorker(real spacing) : spacing_(spacing), thread_([this] { run(); }) {}

SurfaceWorker::~SurfaceWorker() {
  {
    std::lock_guard<std::mutex> lock(m_);
    stop_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

std::uint64_t SurfaceWorker::submit(const std::vector<Vec3>& points) {
  std::uint64_t number = 0;
  {
    std::lock_guard<std::mutex> lock(m_);
    pending_.assign(points.begin(), points.end());
    has_pending_ = true;
    number = pending_number_ = ++submitted_;
  }
  cv_.notify_one();
  return number;
}

bool SurfaceWorker::take(SurfaceMesh& mesh, std::uint64_t oldest) {
  std::lock_guard<std::mutex> lock(m_);
  if (!has_done_ || done_number_ < oldest) return false;
  std::swap(mesh, done_);
  has_done_ = false;
  return true;
}

void SurfaceWorker::run() {
  pthread_setname_np(pthread_self(), "viewer-surface");  // as top -H and perf show it
  std::vector<Vec3> points;
  for (;;) {
    std::uint64_t number = 0;
    {
      std::unique_lock<std::mutex> lock(m_);
      cv_.wait(lock, [this] { return stop_ || has_pending_; });
      if (stop_) return;
      std::swap(points, pending_);
      has_pending_ = false;
      number = pending_number_;
    }
    SurfaceMesh mesh;
    // On one thread: OpenVDB would take every core, which the simulation and the frames share.
    arena_.execute([&] {
      try {
        mesh = particle_surface(points, spacing_);
      } catch (const std::exception&) {
        mesh = {};  // a paste position that is not finite (a diverged step): no surface this time
      }
    });
    {
      std::lock_guard<std::mutex> lock(m_);
      done_ = std::move(mesh);
      done_number_ = number;
      has_done_ = true;
      ++built_;
    }
    done_cv_.notify_all();
  }
}

bool SurfaceWorker::wait_for(std::uint64_t number, std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(m_);
  return done_cv_.wait_for(lock, timeout, [&] { return done_number_ >= number; });
}

std::uint64_t SurfaceWorker::built() {
  std::lock_guard<std::mutex> lock(m_);
  return built_;
}

}  // namespace dentsph::viewer
