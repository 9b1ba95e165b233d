// Spindrift — particle shifting and transport velocity (plugins/shifting): models that move the
// particles with a velocity slightly other than their own, v + δv, to keep the particle
// distribution regular (Lind et al. 2012, Sun et al. 2017, Adami et al. 2013). sphSchemes
// `shifting { type ...; }`. The core calls computeShift() at the end of every evaluation, after
// the accelerations and before the boundaries' collision (which has the last word on where a
// particle goes: BoundaryModel.hpp); the model writes δv to the fluid field `shiftingVelocity`
// (Scene::shiftingVelocity), which the integrators add in their drift (advectionVelocity in
// Integrator.hpp). A model may also add to the accelerations (the transport-velocity
// formulation's extra stress) in the same call.
#pragma once

#include "Model.hpp"
#include "Step.hpp"

namespace spindrift {

class ShiftingModel : public Model {
public:
    virtual void computeShift(Scene& scene, ParticleSystem& fluid, const Step& step) = 0;
    // The forces the accelerations it adds (if any) exerted on the boundaries, as ForceKind::other
    // (Reactions.hpp); nothing for a model that only shifts. Called right after computeShift when
    // something wants them.
    virtual void addReactions(const Scene& scene, const ParticleSystem& fluid, const Step& step,
                              Reactions& reactions) const = 0;
};

} // namespace spindrift
