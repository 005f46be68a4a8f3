// Particle snapshots that ParaView opens: VTK XML unstructured grids (.vtu, one vertex cell per
// particle, raw appended binary) and a .pvd collection that indexes them by time.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "dentsph/state.hpp"
#include "dentsph/surface.hpp"

namespace dentsph::io {

// Writes the particles of `state` with the fields position, velocity, density, pressure, role,
// bond_count and id. Throws std::runtime_error naming the file if it cannot be written.
void write_vtu(const std::filesystem::path& file, const State& state);

// Writes a surface (dentsph/surface.hpp) as VTK XML polygon data (.vtp: its vertices and
// triangles, raw appended binary). Throws std::runtime_error naming the file if it cannot be written.
void write_vtp(const std::filesystem::path& file, const SurfaceMesh& mesh);

// A .pvd index, rewritten after every add() so that a run cut short is still readable.
class PvdIndex {
 public:
  explicit PvdIndex(std::filesystem::path file) : file_(std::move(file)) {}
  // Records a snapshot file (relative to the .pvd's folder) at simulated time t.
  void add(double t, const std::string& relative_file);
  std::size_t size() const { return entries_.size(); }

 private:
  std::filesystem::path file_;
  std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace dentsph::io
