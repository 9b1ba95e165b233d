// Spindrift — density diffusion (plugins/densityDiffusion): a term in the continuity equation
// that diffuses the density between neighbours (δ-SPH), so that the pressure of a weakly
// compressible fluid loses its high-frequency noise. sphSchemes `densityDiffusion { type ...;
// delta 0.1; }`; it acts on a density that is integrated in time (pressure `density continuity;`),
// and the core refuses it otherwise. addRate() adds its dρ_i/dt to 'rate' for every fluid
// particle, from the current density and positions, on the current lists (PairLoop.hpp).
#pragma once

#include "ModelContext.hpp"

namespace spindrift {

class DensityDiffusion {
public:
    virtual ~DensityDiffusion() = default;
    virtual void initialise(Scene&) {}
    virtual void addRate(const Scene& scene, std::vector<Scalar>& rate) const = 0;
};

} // namespace spindrift
