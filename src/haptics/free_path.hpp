// Free moves (docs/haptics.md, "Free moves"): how much of a move of the instrument keeps clear of
// the paste and the walls. The virtual coupling's proxy is slowed to the step's velocity limit because a tool
// that outruns the solver makes the paste explode; where no paste is within reach of the move that
// reason is gone, and the proxy goes where the hand is at once.
#pragma once

#include <cstdint>
#include <vector>

#include "dentsph/pose.hpp"
#include "dentsph/state.hpp"

namespace dentsph::haptics {

// The share t in [0, 1] of the move of the instrument from pose `from` to pose `to` (scene frame)
// before some tool particle, moving along the straight segment between its two places, comes
// within `reach` (m) of a particle it interacts with (paste or wall: any but the tool's own): 1
// when the whole move is clear, 0 when a tool particle is within reach already. (Walls count: a
// scene's walls of particles, such as a container's, push the simulated tool as paste does; the
// tooth is held by the hard contact as well.) `tools` is scratch (the tool particles' indices;
// it keeps its capacity between calls).
real free_share(const State& state, const Pose& from, const Pose& to, real reach, std::vector<std::uint32_t>& tools);

}  // namespace dentsph::haptics
