// Spindrift — what a model is handed with each call of a step: the time and Δt of the evaluation
// (never a captured variable), and the core's services. Models never hold one another; where a
// model needs what another one does (a pressure solver carrying its iterate to walls of their
// own pressure, a prediction of the positions the integrator will move the particles to), it
// asks the core, which calls whichever model the case named.
#pragma once

#include "Scene.hpp"

#include <vector>

namespace spindrift {

class StepServices {
public:
    virtual ~StepServices() = default;
    // Whether a boundary has a pressure of its own (adami) that follows the fluid's: a solver
    // that changes the fluid's pressure in its iterations then calls updateBoundaryPressure.
    virtual bool boundariesHaveOwnPressure(const Scene&) const = 0;
    // The boundary model's pressure (and density) of the boundaries of their own pressure, from
    // pressure p of 'fluid' (a solver's iterate); nothing without such boundaries.
    virtual void updateBoundaryPressure(Scene&, const ParticleSystem& fluid, const std::vector<Scalar>& p) const = 0;
    // The drift of 'fluid' over dt with velocities v: x_i = x_i + dt (v_i + δv_i), δv the shifting
    // model's transport correction (when the case names one), wrapped into a periodic domain;
    // into 'x' (which may be the system's own positions). Integrators move the particles with
    // it, and a solver that predicts where they go (dfsph's check) predicts with it.
    virtual void drift(const Scene&, const ParticleSystem& fluid, Scalar dt, const std::vector<Vec3>& v,
                       std::vector<Vec3>& x) const = 0;
    // Positions into a periodic domain (after an integrator's own drift formula).
    virtual void wrap(const Scene&, const ParticleSystem& fluid, std::vector<Vec3>& x) const = 0;
    // Whether the pressure model integrates the density of 'fluid' in time (continuity).
    virtual bool integratesDensity(const ParticleSystem& fluid) const = 0;
    // ρ_i += dt ρ̇_i for an integrated density (nothing otherwise): the continuity equation
    // (Monaghan 1992), with the density diffusion's term when the case names one, from the
    // system's current velocities — those the particles move with over the step — at the
    // positions the step starts from (call it before the drift, while the lists are theirs):
    // a symplectic pairing, as the velocity's. (A rate of the old velocities makes the
    // density–velocity acoustic waves grow every step: a tank at rest erupted in 0.1 s.)
    virtual void advanceDensity(Scene&, ParticleSystem& fluid, Scalar dt) const = 0;
};

// One evaluation's time and step, and the core's services.
struct Step {
    double time;
    Scalar dt;
    const StepServices& core;
};

class BoundaryModel;
class DensityDiffusion;
class PressureModel;

// The services from the models a case names (any may be absent): what Simulation gives its
// models, and what a test or benchmark that drives models by hand gives them.
class CoreServices final : public StepServices {
public:
    struct Models {
        BoundaryModel* boundary = nullptr;
        const DensityDiffusion* densityDiffusion = nullptr;
        const PressureModel* pressure = nullptr; // whether it integrates the density
        bool shifting = false;                   // a shifting model writes the fluids' shiftingVelocity
    };
    CoreServices() = default;
    explicit CoreServices(Models models, Periodicity periodic = {}) : models_(models), periodic_(periodic) {}
    void setModels(Models models) { models_ = models; }

    bool boundariesHaveOwnPressure(const Scene&) const override;
    void updateBoundaryPressure(Scene&, const ParticleSystem& fluid, const std::vector<Scalar>& p) const override;
    void drift(const Scene&, const ParticleSystem& fluid, Scalar dt, const std::vector<Vec3>& v,
               std::vector<Vec3>& x) const override;
    void wrap(const Scene&, const ParticleSystem& fluid, std::vector<Vec3>& x) const override;
    bool integratesDensity(const ParticleSystem& fluid) const override;
    void advanceDensity(Scene&, ParticleSystem& fluid, Scalar dt) const override;

private:
    Models models_{};
    Periodicity periodic_;
};

} // namespace spindrift
