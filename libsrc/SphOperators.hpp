// Spindrift — inline SPH building blocks shared by the model plugins: pair loops over the
// step's neighbour lists, summation density and the symmetric pressure gradient. Models call
// these inside their own per-step loops (no virtual call per pair).
#pragma once

#include "SphSystem.hpp"

namespace spindrift {

// f(j, r_ij, r²) for every neighbour j of particle i in 'list' (positions xi of the set i
// belongs to, xj of the neighbours' set). r_ij is the nearest periodic image when the domain
// is periodic.
template <class F>
inline void forEachNeighbour(const NeighbourList& list, const std::vector<Vec3>& xi,
                             const std::vector<Vec3>& xj, std::size_t i, F&& f) {
    const Vec3 x = xi[i];
    if (list.periodic) {
        for (const Index* it = list.begin(i), *end = list.end(i); it != end; ++it) {
            const Index j = *it;
            Vec3 rij = x - xj[j];
            list.periodic->minimumImage(rij);
            f(j, rij, rij.squaredNorm());
        }
        return;
    }
    for (const Index* it = list.begin(i), *end = list.end(i); it != end; ++it) {
        const Index j = *it;
        const Vec3 rij = x - xj[j];
        f(j, rij, rij.squaredNorm());
    }
}

// Wall particles in the pair sums: b counts with mass scale · weight[b] (Ψ_b of the boundary
// model: scale 1; or a wall volume V_b: scale ρ0); no wall terms when weight is null.
struct WallMasses {
    const Scalar* weight = nullptr;
    Scalar scale = 1;
    // Ψ_b of the boundary model (none without one)
    static WallMasses ofBoundaryModel(const SphSystem& s) {
        return {s.boundaryMass && s.hasBoundary() ? s.boundaryMass->data() : nullptr, Scalar(1)};
    }
};

// ρ_i = m (W(0) + Σ_j W_ij) + Σ_b M_b W_ib at positions x (the current or predicted ones), on
// the step's neighbour lists.
inline void summationDensity(const SphSystem& s, const std::vector<Vec3>& x, std::vector<Scalar>& rho,
                             WallMasses walls) {
    const auto& kt = s.kernel;
    const Scalar m = s.fluid.particleMass();
    const auto& ff = s.search.fluidNeighbours();
    const auto& fb = s.search.boundaryNeighbours();
    const auto& xb = s.boundary.position();
    const Scalar* wb = walls.weight;
    forEachParticleBalanced(s.search, [&](std::size_t i) {
        Scalar sum = kt.W0();
        forEachNeighbour(ff, x, x, i, [&](Index, const Vec3&, Scalar r2) { sum += kt.WSq(r2); });
        Scalar wall = 0;
        if (wb) forEachNeighbour(fb, x, xb, i, [&](Index b, const Vec3&, Scalar r2) { wall += wb[b] * kt.WSq(r2); });
        rho[i] = m * sum + walls.scale * wall;
    });
}
inline void summationDensity(const SphSystem& s, const std::vector<Vec3>& x, std::vector<Scalar>& rho) {
    summationDensity(s, x, rho, WallMasses::ofBoundaryModel(s));
}

// out(i, a_i) for every particle i, with a_i = −Σ_j m (q_i + q_j) ∇_i W_ij − Σ_b M_b (q_i + q_b) ∇_i W_ib
// the symmetric pressure acceleration from q = p/ρ² at positions x; q_b = q_i when the
// boundary mirrors pressure, else the wall's own p_b/ρ_b². 'out' lets a solver use a_i in the
// same pass (PCISPH predicts the next positions with it).
template <class Out>
inline void symmetricPressureAcceleration(const SphSystem& s, const std::vector<Vec3>& x, const Scalar* q,
                                          WallMasses walls, Out&& out) {
    const auto& kt = s.kernel;
    const Scalar m = s.fluid.particleMass(), wallScale = walls.scale;
    const auto& ff = s.search.fluidNeighbours();
    const auto& fb = s.search.boundaryNeighbours();
    const auto& xb = s.boundary.position();
    const Scalar* wb = walls.weight;
    const bool mirrored = s.boundaryPressureMirrored;
    const auto& pb = s.boundary.pressure();
    const auto& rhob = s.boundary.density();
    forEachParticleBalanced(s.search, [&](std::size_t i) {
        const Scalar qi = q[i];
        Vec3 acc = Vec3::Zero();
        forEachNeighbour(ff, x, x, i,
                         [&](Index j, const Vec3& rij, Scalar r2) { acc -= (qi + q[j]) * kt.gradWSq(rij, r2); });
        acc *= m;
        if (wb) {
            Vec3 wall = Vec3::Zero();
            forEachNeighbour(fb, x, xb, i, [&](Index b, const Vec3& rib, Scalar r2) {
                const Scalar qb = mirrored ? qi : pb[b] / (rhob[b] * rhob[b]);
                wall -= (wb[b] * (qi + qb)) * kt.gradWSq(rib, r2);
            });
            acc += wallScale * wall;
        }
        out(i, acc);
    });
}

// a_i += the symmetric pressure acceleration of p and ρ (above). p/ρ² is taken once per
// particle (in 'pOverRho2', the caller's scratch storage), not once per pair.
inline void addSymmetricPressureAcceleration(const SphSystem& s, const std::vector<Vec3>& x,
                                             const std::vector<Scalar>& p, const std::vector<Scalar>& rho,
                                             std::vector<Vec3>& a, WallMasses walls,
                                             std::vector<Scalar>& pOverRho2) {
    const std::size_t n = x.size();
    pOverRho2.resize(n);
    Scalar* q = pOverRho2.data();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) q[i] = p[i] / (rho[i] * rho[i]);
    symmetricPressureAcceleration(s, x, q, walls, [&](std::size_t i, const Vec3& acc) { a[i] += acc; });
}

} // namespace spindrift
