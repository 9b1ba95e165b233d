// Spindrift — density diffusion (plugins/densityDiffusion): a term in the continuity equation
// that diffuses the density between neighbours (δ-SPH), so that the pressure of a weakly
// compressible fluid loses its high-frequency noise. sphSchemes `densityDiffusion { type ...;
// delta 0.1; }`; it acts on a density that is integrated in time (pressure `density continuity;`),
// and the core refuses it otherwise. densityRate() writes dρ_i/dt of the continuity equation
// with the diffusion in it to 'rate' for every fluid particle, from the current density,
// velocities and positions, on the current lists: both in one pass over the pairs
// (continuityDensityRate with the model's pair term, PairLoop.hpp).
#pragma once

#include "ModelContext.hpp"

namespace spindrift {

class DensityDiffusion {
public:
    virtual ~DensityDiffusion() = default;
    virtual void initialise(Scene&) {}
    virtual void densityRate(const Scene& scene, std::vector<Scalar>& rate) const = 0;
};

} // namespace spindrift
