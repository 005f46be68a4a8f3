// The data behind a PreparedTooth (shared by the carving, the queries and the sampler).
#pragma once

#include "dentsph/tooth.hpp"
#include "tooth/cavity_shape.hpp"

namespace dentsph {

struct PreparedTooth::Impl {
  MeshDistance tooth;
  ToothFrame frame;  // origin at the occlusal reference
  CavityParams params;
  tooth::CavityShape shape;  // in frame coordinates
  CavityReport report;
  Bounds cavity_local;  // frame coordinates, holds every point of cavity and tooth
  Bounds cavity_world;
};

}  // namespace dentsph
