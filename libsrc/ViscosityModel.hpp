// Spindrift — non-pressure forces: viscosity (plugins/viscosity, one per case in sphSchemes
// `viscosity { }`) and further forces (plugins/forces, any number in sphSchemes
// `forces { name { type ...; } }`, e.g. vorticity confinement, surface tension).
// Each adds its result to the fluid system's acceleration(), as a pair term through the core's
// pair loop (PairLoop.hpp: addPairAcceleration), once per evaluation and fluid system. They run
// after the density is known and before the pressure model, so iterative pressure solvers
// predict with the non-pressure accelerations. A viscosity limits the step by its viscous limit
// (Model::maxTimeStep).
#pragma once

#include "Model.hpp"
#include "Step.hpp"

#include <cmath>

namespace spindrift {

class ForceModel : public Model {
public:
    virtual void addAcceleration(Scene& scene, ParticleSystem& fluid, const Step& step) = 0;
    // The forces its last addAcceleration of 'fluid' exerted on the boundaries (Reactions.hpp:
    // the reactions of its boundary terms, as viscous for a viscosity, other for another force;
    // nothing for a model without a boundary term). Called right after addAcceleration when
    // something wants them.
    virtual void addReactions(const Scene& scene, const ParticleSystem& fluid, const Step& step,
                              Reactions& reactions) const = 0;
    virtual ResultKind result() const { return ResultKind::acceleration; }
};

// The viscous step limit of Morris, Fox & Zhu (1997), Δt ≤ 0.125 h_s²/ν, on the smoothing length
// h_s = h/2 (on the support radius itself the limit is 4 times too large: Poiseuille flow blows
// up); +∞ for ν = 0.
inline double viscousTimeStepLimit(const Scene& s, double nu) {
    const double h = s.constants.supportRadius;
    return nu > 0 ? 0.125 * 0.25 * h * h / nu : std::numeric_limits<double>::infinity();
}

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
