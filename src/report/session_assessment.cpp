// A realtime session's assessment (session_assessment.hpp).
#include "report/session_assessment.hpp"

#include <stdexcept>

#include "dentsph/assess.hpp"

namespace dentsph::report {

std::string session_assessment_json(const Scene& scene, const State& state, const Recording& recording) {
  if (!scene.tooth) throw std::invalid_argument("session_assessment_json: the scene has no tooth");
  AssessParams p;
  p.spacing = scene.material_spacing > 0 ? scene.material_spacing : default_tooth_spacing;
  const CavityAssessor assessor(*scene.tooth, p);
  ForceStats forces;
  for (const StepSample& s : recording.steps) forces.add(s.tool_force, scene.model.dt);
  return assessment_json(assessor.assess(state, scene.model, forces, recording.force_scale));
}

}  // namespace dentsph::report
