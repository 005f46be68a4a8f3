// The paste drawn as its surface (paste_surface_view.hpp).
#include "paste_surface_view.hpp"

#include <array>

#include "dentsph/io/role_colours.hpp"

namespace dentsph::viewer {

namespace {

glm::vec3 paste_colour() {
  const std::array<float, 3> c = io::role_colour(Role::material);
  return {c[0], c[1], c[2]};
}

}  // namespace

PasteSurfaceView::PasteSurfaceView(const Scene& scene, real spacing, bool in_frame)
    : scene_(scene), spacing_(spacing), in_frame_(in_frame), mesh_renderer_(paste_colour()) {}

void PasteSurfaceView::update(const Snapshot& snap, bool on) {
  const bool was_on = was_on_;
  was_on_ = on;
  if (!on) {
    due_ = 0;
    return;
  }
  points_.resize(snap.role.size());
  for (std::size_t i = 0; i < snap.role.size(); ++i) points_[i] = {snap.xyz[3 * i], snap.xyz[3 * i + 1], snap.xyz[3 * i + 2]};
  // The paste within the scene's domain (a diverged step's flung or non-finite paste has none).
  const std::vector<Vec3> paste = paste_within(points_, snap.role, scene_.model.domain_min, scene_.model.domain_max);
  const std::pair<std::uint64_t, std::size_t> key{snap.steps, paste.size()};
  // With the view just turned on, or after a reset (the steps went back), a surface built before
  // is of another paste: nothing is drawn until this paste's is.
  const bool fresh = !was_on || key.first < key_.first;
  if (fresh) mesh_renderer_.upload({}, {});
  // This frame is due the surface of the paste the frame before submitted (0: none).
  const std::uint64_t due = std::exchange(due_, 0);
  if (key != key_ || fresh) {
    if (in_frame_) {
      mesh_ = particle_surface(paste, spacing_);
      mesh_renderer_.upload(mesh_.vertices, mesh_.triangles);
      ++built_in_frame_;
    } else if (fresh || moved(paste)) {
      if (!worker_) worker_ = std::make_unique<SurfaceWorker>(spacing_);
      const std::uint64_t number = worker_->submit(paste);
      if (fresh) oldest_ = number;
      submitted_ = paste;
      due_ = number;
    }
    key_ = key;
  }
  if (worker_ && due != 0 && !fresh) {
    ++frames_due_;
    if (!worker_->wait_for(due, kMaxWait)) ++frames_late_;
  }
  if (worker_ && worker_->take(mesh_, oldest_)) mesh_renderer_.upload(mesh_.vertices, mesh_.triangles);
}

std::uint64_t PasteSurfaceView::built() const { return built_in_frame_ + (worker_ ? worker_->built() : 0); }

bool paste_moved(const std::vector<Vec3>& now, const std::vector<Vec3>& built, real tolerance) {
  if (now.size() != built.size()) return true;
  for (std::size_t i = 0; i < now.size(); ++i)
    if (!(norm2(now[i] - built[i]) <= tolerance * tolerance)) return true;
  return false;
}

bool PasteSurfaceView::moved(const std::vector<Vec3>& paste) const {
  return paste_moved(paste, submitted_, kStillFraction * spacing_ / SurfaceParams{}.voxels_per_spacing);
}

}  // namespace dentsph::viewer
