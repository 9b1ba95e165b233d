// Spindrift — pressure model interface (plugins/pressure).
//
// Called once per force evaluation, never per pair: the model loops over particles and their
// neighbours through the core's pair loop (PairLoop.hpp). computeDensity() runs first (the
// boundary and viscosity models may read the density and pressure); addPressureAcceleration()
// then adds the pressure's result to fluid.acceleration(), which holds the non-pressure
// accelerations on entry. Iterative solvers (PCISPH, PBF, DFSPH) run their predict–correct loop
// inside addPressureAcceleration() on the step's neighbour lists, predicting with the step's Δt;
// what the result is (an acceleration, Δv/Δt or Δx/Δt²) the model declares (result()).
// Every model writes a pressure in Pa to fluid.pressure(), which probes and walls read.
#pragma once

#include "ModelContext.hpp"

namespace spindrift {

class PressureModel {
public:
    virtual ~PressureModel() = default;
    // The sound speed c0 [m/s] of the model's equation of state, resolved at set-up before any
    // model initialises (it goes into Scene::constants); 0 for incompressible solvers.
    // 'constants' holds everything but the sound speed itself.
    virtual Scalar soundSpeed(const SceneConstants& /*constants*/, const PhysicalParameters&) const { return 0; }
    // γ of its Tait equation of state (0 without one): with the sound speed, the core's
    // SceneConstants::densityAt inverts the equation of state for walls of their own pressure.
    virtual Scalar eosExponent() const { return 0; }
    virtual void initialise(Scene&) {}
    virtual void computeDensity(Scene& scene) = 0;
    virtual void addPressureAcceleration(Scene& scene, Scalar dt) = 0;
    virtual ResultKind result() const { return ResultKind::acceleration; }
    virtual SolverStats lastSolve() const { return {}; }
    virtual bool isIterative() const { return false; }
};

} // namespace spindrift
