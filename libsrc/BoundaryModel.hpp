// Spindrift — boundary model interface (plugins/boundary): how the particles of boundary systems
// (walls and bodies) act on the fluid. initialise() runs once every system exists, before the
// pressure model's: it gives each boundary its particles' masses M_b and says whether it mirrors
// the fluid's pressure or has its own (ParticleSystem::mass, pressureMirrored, viscousVelocity).
// update() runs at every evaluation once the fluids' density and pressure are known (after
// computeDensity), e.g. to extrapolate the boundaries' pressure; a pressure solver that changes
// a fluid's pressure in its iterations has the core carry the change to the boundaries
// (StepServices::updateBoundaryPressure, which calls updatePressure). correctAcceleration() runs
// after the pressure model, when a fluid's accelerations are complete: there every boundary
// model applies the collision of fluid particles that the step would carry into a boundary
// (WallCollision.hpp, the model dictionary's `collision { }`; on at the faces by default,
// `collision no;` off) and reports the force that puts on each boundary (addReactions, right
// after it, when something wants the reactions). A model reads its collision in its constructor
// and initialises it in initialise().
#pragma once

#include "Model.hpp"
#include "Step.hpp"
#include "WallCollision.hpp"

namespace spindrift {

class BoundaryModel : public Model {
public:
    void initialise(Scene& scene) override = 0;
    virtual void update(Scene&, const Step&) {}
    // The boundaries' own pressure from pressure p of 'fluid' (no-op for mirrored boundaries).
    virtual void updatePressure(Scene&, const ParticleSystem& /*fluid*/, const std::vector<Scalar>& /*p*/) {}
    virtual void correctAcceleration(Scene& s, ParticleSystem& fluid, const Step& step) { collision_.apply(s, fluid, step.dt); }
    virtual void addReactions(const Scene& s, const ParticleSystem& fluid, const Step& step, Reactions& r) const {
        collision_.addReactions(s, fluid, step.dt, r);
    }

protected:
    WallCollision collision_;
};

} // namespace spindrift
