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

// ρ_i = m (W0 + Σ_j W_ij) + ρ0 Σ_b V_b W_ib at positions x, on the step's neighbour lists.
inline void densityWithWalls(const SphSystem& s, const std::vector<Vec3>& x, const std::vector<Scalar>& wallVolume,
                             std::vector<Scalar>& rho) {
    const auto& kt = s.kernel;
    const Scalar m = s.fluid.particleMass(), rho0 = s.physics.rho0;
    const auto& ff = s.search.fluidNeighbours();
    const auto& fb = s.search.boundaryNeighbours();
    const auto& xb = s.boundary.position();
    const Scalar* vb = wallVolume.data();
    const bool walls = s.hasBoundary();
    const std::size_t n = x.size();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
        Scalar sum = kt.W0();
        forEachNeighbour(ff, x, x, i, [&](Index, const Vec3&, Scalar r2) { sum += kt.W(std::sqrt(r2)); });
        Scalar wall = 0;
        if (walls)
            forEachNeighbour(fb, x, xb, i, [&](Index b, const Vec3&, Scalar r2) { wall += vb[b] * kt.W(std::sqrt(r2)); });
        rho[i] = m * sum + rho0 * wall;
    }
}

// a_i −= Σ_j m (p_i/ρ_i² + p_j/ρ_j²) ∇_i W_ij + Σ_b ρ0 V_b (p_i/ρ_i² + p_b/ρ_b²) ∇_i W_ib at the
// current positions, with p_b = p_i, ρ_b = ρ_i when the boundary model mirrors pressure.
inline void addPressureAccelerationWithWalls(const SphSystem& s, const std::vector<Scalar>& wallVolume,
                                             const std::vector<Scalar>& p, const std::vector<Scalar>& rho,
                                             std::vector<Vec3>& a) {
    const auto& kt = s.kernel;
    const Scalar m = s.fluid.particleMass(), rho0 = s.physics.rho0;
    const auto& x = s.fluid.position();
    const auto& ff = s.search.fluidNeighbours();
    const auto& fb = s.search.boundaryNeighbours();
    const auto& xb = s.boundary.position();
    const auto& pb = s.boundary.pressure();
    const auto& rhob = s.boundary.density();
    const Scalar* vb = wallVolume.data();
    const bool walls = s.hasBoundary(), mirrored = s.boundaryPressureMirrored;
    const std::size_t n = x.size();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
        const Scalar pi = p[i] / (rho[i] * rho[i]);
        Vec3 acc = Vec3::Zero();
        forEachNeighbour(ff, x, x, i, [&](Index j, const Vec3& rij, Scalar r2) {
            acc -= (m * (pi + p[j] / (rho[j] * rho[j]))) * kt.gradW(rij, std::sqrt(r2));
        });
        if (walls)
            forEachNeighbour(fb, x, xb, i, [&](Index b, const Vec3& rib, Scalar r2) {
                const Scalar pbTerm = mirrored ? pi : pb[b] / (rhob[b] * rhob[b]);
                acc -= (rho0 * vb[b] * (pi + pbTerm)) * kt.gradW(rib, std::sqrt(r2));
            });
        a[i] += acc;
    }
}

} // namespace spindrift
