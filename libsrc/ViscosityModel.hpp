// Spindrift — non-pressure forces: viscosity (plugins/viscosity, one per case in sphSchemes
// `viscosity { }`) and further forces (plugins/forces, any number in sphSchemes
// `forces { name { type ...; } }`, e.g. vorticity confinement, surface tension).
// Each adds its result to fluid.acceleration(), as a pair term through the core's pair loop
// (PairLoop.hpp: addPairAcceleration). They run after the density is known and before the
// pressure model, so iterative pressure solvers predict with the non-pressure accelerations.
#pragma once

#include "ModelContext.hpp"

namespace spindrift {

class ForceModel {
public:
    virtual ~ForceModel() = default;
    virtual void initialise(Scene&) {}
    virtual void addAcceleration(Scene& scene, Scalar dt) = 0;
    virtual ResultKind result() const { return ResultKind::acceleration; }
    // Kinematic viscosity for the viscous time-step limit Δt <= 0.125 h²/ν (0 = no limit).
    virtual Scalar timeStepViscosity() const { return 0; }
};

class ViscosityModel : public ForceModel {};
class ExtraForce : public ForceModel {};

// What a viscous pair term reads of particle i before its pairs (PairLoop.hpp): its velocity and
// density. The artificial, laminar and XSPH terms derive from it.
struct VelocityDensityTerm {
    struct Particle {
        Vec3 v;
        Scalar rho;
    };
    const Vec3* v;
    const Scalar* rho;
    Particle particle(std::size_t i) const { return {v[i], rho[i]}; }
};

} // namespace spindrift
