// Spindrift — density diffusion (plugins/densityDiffusion): a term in the continuity equation
// that diffuses the density between neighbours (δ-SPH), so that the pressure of a weakly
// compressible fluid loses its high-frequency noise. sphSchemes `densityDiffusion { type ...;
// delta 0.1; }`; it acts on a density that is integrated in time (pressure `density continuity;`),
// and the core leaves it out (with a warning) otherwise. densityRate() writes dρ_i/dt of the
// continuity equation with the diffusion in it to 'rate' for every particle of the fluid, from
// the current density, velocities and positions, on the current lists: both in one pass over
// the pairs (continuityDensityRate with the model's pair term, PairLoop.hpp). The core calls it
// when it advances the density (StepServices::advanceDensity).
#pragma once

#include "Model.hpp"
#include "Parallel.hpp"

namespace spindrift {

class DensityDiffusion : public Model {
public:
    virtual void densityRate(const Scene& scene, const ParticleSystem& fluid, std::vector<Scalar>& rate) const = 0;

protected:
    // 1/ρ_j of every fluid particle, taken once a call: the diffusion terms divide by ρ_j, and a
    // multiplication per pair is cheaper than a division. (ρ_i − ρ_j)·(1/ρ_j) stays exactly zero
    // for a uniform density.
    const Scalar* inverseDensity(const ParticleSystem& fluid) const {
        const auto& rho = fluid.particles.density();
        inverseDensity_.resize(rho.size());
        forEachIndex(rho.size(), [&](std::size_t i) { inverseDensity_[i] = 1 / rho[i]; });
        return inverseDensity_.data();
    }

private:
    mutable std::vector<Scalar> inverseDensity_; // scratch of inverseDensity()
};

} // namespace spindrift
