// Spindrift — viscosity (and other non-pressure force) interface (plugins/viscosity).
// Adds its acceleration to fluid.acceleration(); loops over neighbours itself. Runs after
// the density is known and before the pressure model.
#pragma once

#include "ModelContext.hpp"

namespace spindrift {

class ViscosityModel {
public:
    virtual ~ViscosityModel() = default;
    virtual void initialise(SphSystem&) {}
    virtual void addAcceleration(SphSystem& system, Scalar dt) = 0;
    // Kinematic viscosity for the viscous time-step limit Δt <= 0.125 h²/ν (0 = no limit).
    virtual Scalar timeStepViscosity() const { return 0; }
};

} // namespace spindrift
