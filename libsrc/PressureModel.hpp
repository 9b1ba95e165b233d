// Spindrift — pressure model interface (plugins/pressure).
//
// Called once per force evaluation, never per pair: the model loops over particles and their
// neighbours itself. computeDensity() runs first (viscosity models may read the density);
// addPressureAcceleration() then adds the pressure acceleration to fluid.acceleration(),
// which holds the non-pressure accelerations on entry. Iterative solvers (PCISPH, PBF) run
// their predict–correct loop inside addPressureAcceleration() on the step's neighbour lists,
// predicting with the step's Δt; position-based solvers return Δx/Δt² as an acceleration.
#pragma once

#include "ModelContext.hpp"

namespace spindrift {

class PressureModel {
public:
    virtual ~PressureModel() = default;
    virtual void initialise(SphSystem&) {}
    virtual void computeDensity(SphSystem& system) = 0;
    virtual void addPressureAcceleration(SphSystem& system, Scalar dt) = 0;
    // True when the model's last solve left the neighbour lists (and its density) of exactly
    // the current fluid positions, so the next evaluation need not search (dfsph's
    // checkPositions searches at the positions its step leads to).
    virtual bool searchedAt(const SphSystem&) const { return false; }
    // The particles are about to be re-sorted (new i = old order[i]) while searchedAt() holds:
    // the model reorders what it keeps for the next evaluation (the neighbour lists are still
    // in the old order here; they are relabelled after the fluid).
    virtual void permute(const SphSystem&, const std::vector<Index>& /*order*/) {}
    // Numerical sound speed for the CFL limit; 0 for incompressible solvers.
    virtual Scalar soundSpeed() const { return 0; }
    virtual SolverStats lastSolve() const { return {}; }
    virtual bool isIterative() const { return false; }
};

} // namespace spindrift
