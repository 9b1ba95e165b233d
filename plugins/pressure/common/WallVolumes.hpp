// Wall-particle volumes for the incompressible pressure solvers (pcisph, pbf, relaxedPbf) and
// the density summation and symmetric pressure gradient written on them.
//
//   boundaryVolume adaptive;  V_b = Ψ_b/ρ0 from the boundary model (Akinci et al. 2012:
//                             1/Σ_k W_bk; seed 002's "adaptive boundary mass"). Meant for one
//                             layer of wall particles: on several lattice layers it over-counts
//                             the wall (a fluid particle next to a flat 3-layer wall starts
//                             ~8 % above ρ0), which an incompressible solver removes in its
//                             first step by pushing the fluid off the wall.
//   boundaryVolume uniform;   V_b = m/ρ0, the fluid particle's volume: walls sampled on the
//                             fluid lattice with layers·Δx ≥ h (the tutorials' containers)
//                             then give exactly ρ0 to a fluid particle at rest beside them.
#pragma once

#include "Dictionary.hpp"
#include "SphOperators.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace spindrift {

inline bool readAdaptiveBoundaryVolume(const Dictionary& d, bool adaptiveByDefault) {
    return d.getWordOrDefault("boundaryVolume", {"adaptive", "uniform"}, adaptiveByDefault ? "adaptive" : "uniform") ==
           "adaptive";
}

// V_b for every wall particle (static walls; call after the boundary model's initialise()).
inline std::vector<Scalar> wallVolumes(const SphSystem& s, bool adaptive, const std::string& model) {
    const Scalar rho0 = s.physics.rho0;
    std::vector<Scalar> v(s.boundary.size(), s.fluid.particleMass() / rho0);
    if (adaptive && s.hasBoundary()) {
        if (!s.boundaryMass)
            throw std::runtime_error(model + ": boundaryVolume adaptive needs a boundary model that sets the wall "
                                             "particles' volumes (e.g. akinci)");
        for (std::size_t b = 0; b < v.size(); ++b) v[b] = (*s.boundaryMass)[b] / rho0;
    }
    return v;
}

// Wall particles of volume V_b in the pair sums (mass ρ0 V_b).
inline WallMasses wallMassesOf(const SphSystem& s, const std::vector<Scalar>& wallVolume) {
    return {s.hasBoundary() ? wallVolume.data() : nullptr, s.physics.rho0};
}

// ρ_i = m (W0 + Σ_j W_ij) + ρ0 Σ_b V_b W_ib at positions x, on the step's neighbour lists.
inline void densityWithWalls(const SphSystem& s, const std::vector<Vec3>& x, const std::vector<Scalar>& wallVolume,
                             std::vector<Scalar>& rho) {
    summationDensity(s, x, rho, wallMassesOf(s, wallVolume));
}

} // namespace spindrift
