// Spindrift — time integrator interface (plugins/integrators).
//
// step() advances fluid positions and velocities by dt. It calls evaluate() whenever it needs
// accelerations at the current positions and velocities: evaluate() rebuilds the neighbour
// lists and fills fluid.acceleration() (density, boundary, non-pressure, pressure). So
// multi-stage and multi-step schemes fit one interface. Per-particle state that must survive
// between steps (history) lives in fields registered on the fluid set in initialise(), so it
// is re-sorted with the particles and written for restarts.
#pragma once

#include "ModelContext.hpp"

#include <functional>

namespace spindrift {

class Integrator {
public:
    using Evaluate = std::function<void()>;
    virtual ~Integrator() = default;
    virtual void initialise(SphSystem&) {}
    // The state (every restart field, system.step and system.time) was just read from a time
    // directory: restore any non-field state so the run continues as if never interrupted.
    virtual void restarted(SphSystem&) {}
    virtual void step(SphSystem& system, Scalar dt, const Evaluate& evaluate) = 0;
};

} // namespace spindrift
