#include "Step.hpp"

#include "BoundaryModel.hpp"
#include "DensityDiffusion.hpp"
#include "PairLoop.hpp"
#include "PressureModel.hpp"

namespace spindrift {

bool CoreServices::boundariesHaveOwnPressure(const Scene& s) const {
    for (const ParticleSystem* b : s.boundaries())
        if (b->mass && !b->pressureMirrored) return true;
    return false;
}

void CoreServices::updateBoundaryPressure(Scene& s, const ParticleSystem& fluid, const std::vector<Scalar>& p) const {
    if (models_.boundary) models_.boundary->updatePressure(s, fluid, p);
}

void CoreServices::drift(const Scene&, const ParticleSystem& fluid, Scalar dt, const std::vector<Vec3>& v,
                         std::vector<Vec3>& x) const {
    const auto& from = fluid.particles.position();
    const std::vector<Vec3>* shift = models_.shifting ? fluid.particles.findVector("shiftingVelocity") : nullptr;
    const Periodicity& periodic = periodic_;
    if (&x != &from) x = from; // (its ghosts stay where they are)
    forEachIndex(fluid.ownedSize(), [&](std::size_t i) {
        Vec3 xi = from[i] + dt * (shift ? Vec3(v[i] + (*shift)[i]) : v[i]);
        if (periodic.any()) periodic.wrap(xi);
        x[i] = xi;
    });
}

void CoreServices::wrap(const Scene&, const ParticleSystem& fluid, std::vector<Vec3>& x) const {
    const Periodicity& periodic = periodic_;
    if (periodic.any()) forEachIndex(fluid.ownedSize(), [&](std::size_t i) { periodic.wrap(x[i]); });
}

bool CoreServices::integratesDensity(const ParticleSystem& fluid) const {
    return fluid.isFluid() && models_.pressure && models_.pressure->integratesDensity();
}

void CoreServices::advanceDensity(Scene& s, ParticleSystem& fluid, Scalar dt) const {
    if (!integratesDensity(fluid)) return;
    auto& rate = fluid.particles.addScalar("densityRate", {false, false, true});
    if (models_.densityDiffusion) models_.densityDiffusion->densityRate(s, fluid, rate);
    else continuityDensityRate(s, fluid, rate);
    auto& rho = fluid.particles.density();
    forEachIndex(fluid.ownedSize(), [&](std::size_t i) { rho[i] += dt * rate[i]; });
}

} // namespace spindrift
