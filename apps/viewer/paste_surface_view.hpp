// The paste drawn as its surface (dentsph/surface.hpp, key S): built again for each new snapshot,
// by a worker beside the frames (surface_worker.hpp) or, for a screenshot, in the frame, so that
// the picture shows the paste it was asked of (docs/viewer.md).
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "dentsph/scene.hpp"
#include "dentsph/surface.hpp"
#include "renderers.hpp"
#include "sim_session.hpp"
#include "surface_worker.hpp"

namespace dentsph::viewer {

// Whether the paste `now` differs from the paste `built` a surface was made of: another count, or a
// particle farther than `tolerance` (m) from where it was (in the same order: a State reordered
// since counts as moved).
bool paste_moved(const std::vector<Vec3>& now, const std::vector<Vec3>& built, real tolerance);

class PasteSurfaceView {
 public:
  // `spacing`: the paste's particle spacing (m); `in_frame`: build each surface in the frame.
  PasteSurfaceView(const Scene& scene, real spacing, bool in_frame);

  // Called every frame with the newest snapshot: while `on`, submits its paste when it is new (by
  // step and particle count) and has moved since the paste last submitted (moved()), and uploads
  // the newest surface finished. The frames keep pace with the surface: a frame after one that
  // submitted a paste waits for that paste's surface (built while the frame before was drawn), at
  // most kMaxWait, so that while the paste moves every frame draws a surface one frame old. A
  // screenshot's surface (in_frame) is built from its own paste.
  void update(const Snapshot& snap, bool on);
  void draw(const ViewUniforms& u) { mesh_renderer_.draw(u); }
  // The surfaces built so far (by the worker, or in the frame).
  std::uint64_t built() const;
  // The frames that were due the surface of the frame before's paste, and those of them that drew
  // an older one (it was not finished within kMaxWait).
  std::uint64_t frames_due() const { return frames_due_; }
  std::uint64_t frames_late() const { return frames_late_; }

  // The longest a frame waits for its surface: a paste too large to be built at the graphics rate
  // slows the frames to no fewer than 10 a second, and then they draw the newest surface finished.
  static constexpr std::chrono::milliseconds kMaxWait{100};

  // A paste particle moving less than this share of a voxel changes its surface by less than that:
  // paste at rest (settled, or curing) is not built again frame after frame.
  static constexpr real kStillFraction = 0.1;

 private:
  // Whether `paste` differs from the paste last submitted (paste_moved, by kStillFraction of a voxel).
  bool moved(const std::vector<Vec3>& paste) const;
  const Scene& scene_;
  const real spacing_;
  const bool in_frame_;
  MeshRenderer mesh_renderer_;
  std::unique_ptr<SurfaceWorker> worker_;
  // The paste last submitted: its step and its particles (a paused simulation publishes the same
  // paste again; a dispense adds to it).
  std::pair<std::uint64_t, std::size_t> key_{~std::uint64_t(0), 0};
  std::uint64_t oldest_ = 0;  // the worker's surfaces from before this one are of another paste
  bool was_on_ = false;
  std::vector<Vec3> points_;
  std::vector<Vec3> submitted_;  // the paste of the surface last submitted to the worker
  std::uint64_t built_in_frame_ = 0;
  std::uint64_t due_ = 0;  // the worker's paste the next frame is due the surface of (0: none)
  std::uint64_t frames_due_ = 0, frames_late_ = 0;
  SurfaceMesh mesh_;
};

}  // namespace dentsph::viewer
