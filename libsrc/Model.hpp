// Spindrift — what every model kind shares (pressure, viscosity, force, boundary, density
// diffusion, shifting, integrator): its initialise() and the time-step limit it may declare.
#pragma once

#include "ModelContext.hpp"

#include <limits>

namespace spindrift {

// What the core has measured of the state a step starts from, for the models' step limits.
struct StateSpeeds {
    double fluid = 0; // the largest speed |v| of a fluid particle [m/s] (the fluids' own particles)
};

class Model {
public:
    virtual ~Model() = default;
    // Called once every system exists and Scene::constants are resolved, before the first
    // evaluation, in the order: boundary, pressure, density diffusion, shifting, viscosity,
    // forces, surface tension, integrator. A model registers the fields it needs here.
    virtual void initialise(Scene&) {}
    // The largest step Δt [s] the model is stable with at the current state (+∞: no limit of its
    // own). The core takes the smallest over every model, the CFL condition on the sound and
    // flow speeds and the acceleration limit (e.g. the viscous limit 0.125 h_s²/ν of Morris et
    // al. 1997, a capillary limit of surface tension, a body's contact stiffness).
    virtual double maxTimeStep(const Scene&, const StateSpeeds&) const { return std::numeric_limits<double>::infinity(); }
};

} // namespace spindrift
