// Spindrift — pressure model interface (plugins/pressure).
//
// Called once per force evaluation for each fluid system, never per pair: the model loops over
// the fluid's particles and their neighbours through the core's pair loop (PairLoop.hpp).
// computeDensity() runs first, for every fluid (the boundary and viscosity models may read the
// density and pressure); addPressureAcceleration() then adds the pressure's result to the
// fluid's acceleration(), which holds the non-pressure accelerations on entry. Iterative solvers
// (PCISPH, PBF, DFSPH) run their predict–correct loop inside addPressureAcceleration() on the
// step's neighbour lists, predicting with the step's Δt; what the result is (an acceleration,
// Δv/Δt or Δx/Δt²) the model declares (result()). Every model writes a pressure in Pa to the
// fluid's pressure(), which probes and walls read. A model whose density is integrated in time
// by the continuity equation says so (integratesDensity): the core then advances it. Right
// after addPressureAcceleration, when something wants the forces on boundaries (a forces
// function object, a rigid body), the core calls addReactions: the model adds the reactions of
// its boundary terms from its final pressure (Reactions.hpp; PairLoop.hpp's addReactions).
#pragma once

#include "Model.hpp"
#include "Step.hpp"

namespace spindrift {

class PressureModel : public Model {
public:
    // The sound speed c0 [m/s] of the model's equation of state, resolved at set-up before any
    // model initialises (it goes into Scene::constants); 0 for incompressible solvers.
    // 'constants' holds everything but the sound speed itself.
    virtual Scalar soundSpeed(const SceneConstants& /*constants*/, const PhysicalParameters&) const { return 0; }
    // γ of its Tait equation of state (0 without one): with the sound speed, the core's
    // SceneConstants::densityAt inverts the equation of state for walls of their own pressure.
    virtual Scalar eosExponent() const { return 0; }
    // The density is integrated in time (continuity) rather than summed from the positions.
    virtual bool integratesDensity() const { return false; }
    virtual void computeDensity(Scene& scene, ParticleSystem& fluid, const Step& step) = 0;
    virtual void addPressureAcceleration(Scene& scene, ParticleSystem& fluid, const Step& step) = 0;
    // The forces its last addPressureAcceleration of 'fluid' exerted on the boundaries.
    virtual void addReactions(const Scene& scene, const ParticleSystem& fluid, const Step& step,
                              Reactions& reactions) const = 0;
    virtual ResultKind result() const { return ResultKind::acceleration; }
    virtual SolverStats lastSolve() const { return {}; }
    virtual bool isIterative() const { return false; }
};

} // namespace spindrift
