// The shared checks of dentsph/limits.hpp.
#include "dentsph/limits.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <system_error>

#include <fmt/format.h>

#include "dentsph/state.hpp"
#include "solver/scratch.hpp"

namespace dentsph::limits {

std::string spacing_problem(real spacing, real h, const char* unit, real scale) {
  if (!std::isfinite(spacing) || !(spacing > 0))
    return fmt::format("must be a positive number, got {} {}", spacing / scale, unit);
  if (spacing > h * (1 + 1e-12))
    return fmt::format("{:.4g} {} is larger than h = {:.4g} {}, so particles would have no neighbours", spacing / scale,
                       unit, h / scale, unit);
  if (spacing < h * min_spacing_per_h * (1 - 1e-12))
    return fmt::format("{:.4g} {} is under h / {:.0f} = {:.4g} {}: about {:.3g} neighbours per particle, whose sums "
                       "would take hours",
                       spacing / scale, unit, 1 / min_spacing_per_h, h * min_spacing_per_h / scale, unit,
                       4.18879 * std::pow(std::min(h / spacing, 1e30), 3));
  return {};
}

std::string spacing_fix(real h, const char* unit, real scale) {
  return fmt::format("give a spacing between h / {:.0f} = {:.4g} {} and h = {:.4g} {} (about h / 2 is usual)",
                     1 / min_spacing_per_h, h * min_spacing_per_h / scale, unit, h / scale, unit);
}

std::uint64_t run_steps(real duration, real dt) {
  const double n = double(duration) / double(dt);
  if (!std::isfinite(n) || n > double(max_run_steps) + 0.5) return max_run_steps + 1;
  return n <= 0 ? 0 : std::uint64_t(std::llround(n));
}

std::string run_length_problem(real duration, real dt) {
  if (run_steps(duration, dt) <= max_run_steps) return {};
  return fmt::format("{:.4g} s in steps of {:.4g} s is {:.3g} steps, over the limit of {} steps of one run", duration,
                     dt, double(duration) / double(dt), max_run_steps);
}

std::uint64_t state_bytes_per_particle(int max_bonds, bool skin) {
  // The per-particle arrays of State (id, role, pos, vel, mass, mu, Kp, rho0, Ka, anchor, rho,
  // pressure, volume, force), counted twice: a vector grown by appending may hold twice its size.
  constexpr std::uint64_t arrays = 4 + 1 + 24 + 24 + 8 * 5 + 24 + 8 * 3 + 24;
  const std::uint64_t by_id = 4 + 8 + 2 + 4 * std::uint64_t(std::max(0, max_bonds));  // index, rho_static, bonds
  constexpr std::uint64_t lists = 4 * 64 + 2;                                       // neighbour lists
  constexpr std::uint64_t grid = 4 + 4 + 3 * 8 + sizeof(PairData);                  // key, order, x y z, pair data
  constexpr std::uint64_t scratch = 24 + 8 + 4 + 1;
  const std::uint64_t kept = skin ? 4 * 64 + 2 + 24 : 0;  // within-h lists, build positions
  // The iisph solver's scratch (IisphScratch), counted whichever solver the scene names, since
  // --solver may choose it after the scene is built: a row of pairs, two counts, eleven vectors
  // (the surface tension's normal among them), seven numbers, four indices and the tool links, and
  // the cg pressure solve's five numbers and its blocks' sums.
  constexpr std::uint64_t iisph = IisphScratch::kPairStride * sizeof(SolverPair) + 2 + 11 * 24 + 7 * 8 + 4 * 4 + 12 +
                                  5 * 8 + sizeof(PressureSums) / IisphScratch::kSumBlock + 1;
  return 2 * arrays + by_id + lists + grid + scratch + kept + iisph;
}

std::uint64_t scene_bytes(std::uint64_t held, std::uint64_t simulated, int max_bonds, bool skin) {
  return held * sizeof(ParticleInit) + simulated * state_bytes_per_particle(max_bonds, skin);
}

std::uint64_t memory_limit_bytes() {
  std::uint64_t limit = max_scene_bytes;
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages > 0 && page > 0) limit = std::min(limit, std::uint64_t(pages) * std::uint64_t(page));
  // A process limited in its address space (ulimit -v): three quarters of it, the rest for the
  // program, its libraries and threads' stacks.
  if (rlimit as{}; getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY)
    limit = std::min(limit, std::uint64_t(as.rlim_cur) / 4 * 3);
  // A smaller limit asked for (a shared machine, the fuzzers): DENTSPH_MEMORY_LIMIT_MB.
  if (const char* mb = std::getenv("DENTSPH_MEMORY_LIMIT_MB")) {
    char* end = nullptr;
    const double v = std::strtod(mb, &end);
    if (end != mb && *end == '\0' && v > 0 && v < 1e12) limit = std::min(limit, std::uint64_t(v * 1024 * 1024));
  }
  return limit;
}

std::string memory_problem(std::uint64_t held, std::uint64_t simulated, int max_bonds, bool skin,
                           std::uint64_t limit_bytes) {
  const std::uint64_t need = scene_bytes(held, simulated, max_bonds, skin);
  if (need <= limit_bytes) return {};
  return fmt::format("needs about {:.3g} GiB ({} particles simulated, {} held as read), over the {:.3g} GiB a scene may "
                     "take here",
                     double(need) / double(1 << 30), simulated, held, double(limit_bytes) / double(1 << 30));
}

std::string file_size_problem(const std::string& file, std::uint64_t limit_bytes, const char* what) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (ec || size <= limit_bytes) return "";
  return fmt::format("{}: {} MB, more than the {} MB {} can be (README, \"Resource limits\")", file, size >> 20,
                     limit_bytes >> 20, what);
}

}  // namespace dentsph::limits
