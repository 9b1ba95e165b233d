// Spindrift — boundary model interface (plugins/boundary): how wall particles act on the fluid.
// initialise() runs once every wall system exists, before the pressure model's: it gives each
// wall its particles' masses M_b and says whether the wall mirrors the fluid's pressure or has
// its own (WallSystem::mass, pressureMirrored, viscousVelocity). update() runs at every
// evaluation once the fluid's density and pressure are known (after computeDensity), e.g. to
// extrapolate the walls' pressure; pressure solvers that change the fluid's pressure in their
// iterations call updatePressure() to carry the change to the walls.
#pragma once

#include "ModelContext.hpp"

namespace spindrift {

class BoundaryModel {
public:
    virtual ~BoundaryModel() = default;
    virtual void initialise(Scene& scene) = 0;
    virtual void update(Scene&) {}
    virtual void updatePressure(Scene&, const std::vector<Scalar>& /*fluidPressure*/) {}
};

} // namespace spindrift
