// The filling's assessment at the end of a realtime session (the offline run assesses its own):
// the final state, with the tool force of every recorded step.
#pragma once

#include <string>

#include "dentsph/haptics/recording.hpp"
#include "dentsph/scene.hpp"

namespace dentsph::report {

// assessment_json() of the state, the forces from the recording's steps at the scene's dt and
// the recording's force scale. The scene must have a tooth.
std::string session_assessment_json(const Scene& scene, const State& state, const Recording& recording);

}  // namespace dentsph::report
