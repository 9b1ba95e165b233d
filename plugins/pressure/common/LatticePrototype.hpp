// Kernel-gradient sums of a prototype particle with a full neighbourhood on the case's initial
// lattice (spacing Δx, dimension 2 or 3): the particle at the origin, neighbours at (i, j, k)·Δx
// with 0 < r < h. Used by PCISPH's pressure scaling δ (Solenthaler & Pajarola 2009, eq. 8;
// docs/MODELS.md §pcisph) and by the position-based solvers to make their relaxation parameters
// resolution-independent.
#pragma once

#include "KernelTable.hpp"
#include "Log.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace spindrift {

struct LatticeGradientSums {
    double gradSumSquared = 0;  // Σ_j ∇W_ij · Σ_j ∇W_ij  (0 on a symmetric lattice)
    double sumGradSquared = 0;  // Σ_j ∇W_ij · ∇W_ij
    int neighbours = 0;         // lattice points with 0 < r < h
};

// Calls f(r_ij, ∇W_ij) for every neighbour j of the prototype particle i at the origin.
template <class F> void forEachLatticeNeighbour(const KernelTable& kernel, double dx, int dimension, F&& f) {
    const double h = kernel.supportRadius();
    const int reach = int(std::ceil(h / dx));
    for (int k = (dimension == 3 ? -reach : 0); k <= (dimension == 3 ? reach : 0); ++k)
        for (int j = -reach; j <= reach; ++j)
            for (int i = -reach; i <= reach; ++i) {
                const Vec3 rij(Scalar(-i * dx), Scalar(-j * dx), Scalar(-k * dx)); // x_i − x_j
                const Scalar r = rij.norm();
                if (r > 0 && r < h) f(rij, kernel.gradW(rij, r));
            }
}

inline LatticeGradientSums latticeGradientSums(const KernelTable& kernel, double dx, int dimension) {
    LatticeGradientSums s;
    Vec3 sum = Vec3::Zero();
    forEachLatticeNeighbour(kernel, dx, dimension, [&](const Vec3&, const Vec3& g) {
        sum += g;
        s.sumGradSquared += double(g.squaredNorm());
        ++s.neighbours;
    });
    s.gradSumSquared = double(sum.squaredNorm());
    return s;
}

// How much PCISPH's correction overshoots on the lattice, at worst. A pressure wave
// p_j = cos(k·x_j) moves the particles (eq. 3, ρ = ρ0) so that the density error of the wave
// falls by β/2 |G(k)|² per unit pressure, G(k) = Σ_j sin(k·r_ij) ∇W_ij, while δ assumes
// β Σ_j |∇W_ij|² (one particle's own response, eq. 8). One correction thus multiplies the wave's
// error by 1 − g(k), g(k) = |G(k)|² / (2 Σ_j |∇W_ij|²), and the iteration diverges for a wave
// with g(k) > 2. The gain grows with the neighbour count: 1.41 for the cubic spline at h = 2Δx
// in 3D, 2.10 for the Wendland C2 at 2.6Δx in 3D, 2.84 at 4Δx in 2D. Returns the maximum of
// g over the wave vectors of the lattice (k_a in [0, π/Δx], 'samples' a side: |G| is even in
// every component of k on the symmetric lattice).
inline double latticeMaxCorrectionGain(const KernelTable& kernel, double dx, int dimension, int samples = 48) {
    std::vector<Vec3> offsets, gradients; // r_ij and ∇W_ij of the prototype's neighbours
    double sumGradSquared = 0;
    forEachLatticeNeighbour(kernel, dx, dimension, [&](const Vec3& rij, const Vec3& g) {
        offsets.push_back(rij);
        gradients.push_back(g);
        sumGradSquared += double(g.squaredNorm());
    });
    if (!(sumGradSquared > 0)) return 0;
    const double step = M_PI / (dx * (samples - 1));
    double gain = 0;
    for (int c = 0; c < (dimension == 3 ? samples : 1); ++c)
        for (int b = 0; b < samples; ++b)
            for (int a = 0; a < samples; ++a) {
                const double kx = a * step, ky = b * step, kz = c * step;
                double gx = 0, gy = 0, gz = 0;
                for (std::size_t n = 0; n < offsets.size(); ++n) {
                    const double w = std::sin(kx * offsets[n][0] + ky * offsets[n][1] + kz * offsets[n][2]);
                    gx += w * gradients[n][0];
                    gy += w * gradients[n][1];
                    gz += w * gradients[n][2];
                }
                gain = std::max(gain, (gx * gx + gy * gy + gz * gz) / (2 * sumGradSquared));
            }
    return gain;
}

// The bound on every Jacobi-type pressure solver's relaxation (pcisph's δ, dfsph's and iisph's ω,
// pbf's and relaxedPbf's position update): no lattice wave is corrected with a gain above 1.8
// (below the 2 where the iteration diverges). A solver's relaxation r corrects the wave k with
// the gain c r g(k), c its gain per unit of relaxation in pcisph's normalisation (pcisph's δ 1;
// dfsph's and iisph's ω 2, their diagonal being the whole of i's response, twice δ's; pbf's
// (1 + ω) 2/(1 + ε/D0)), so r is held to at most 1.8/(c g) with g the kernel's largest gain
// (cubic spline at 2Δx in 3D 1.41, at 2.6Δx in 2D 1.44; Wendland C2 at 2.6Δx in 2D 1.30, at 3Δx
// 1.67, at 2.6Δx in 3D 2.10, at 4Δx in 2D 2.84). Where the bound was applied to the nominal
// relaxation instead of c r (dfsph at ω = 1, relaxedPbf at 1 + ω = 1.5: c r g = 3.6 and 2.7 on
// the Wendland C2 at 4Δx in 2D), the waves beyond 2 were held only by the clamp ρ* ≥ ρ0, and the
// clamp's switching rang the whole column: a still tank's bottom pressure swung ±70–80 % of
// ρ0 g H with a period of 20–30 steps, the Colagrossi far wall's at H/80 by 0.5 ρ0 g H (issue 35).
// Without any bound iisph blew up in a still tank at step 8, dfsph at the Colagrossi dam break's
// corner at H/40, pbf in the Taylor–Green vortex. docs/MODELS.md §jacobiRelaxation.
inline constexpr double maxJacobiCorrectionGain = 1.8;

// pcisph's δ (c = 1, r = 1): the factor it is scaled by, min(1, 1.8/g).
inline double jacobiRelaxationScale(double gain) {
    return gain > maxJacobiCorrectionGain ? maxJacobiCorrectionGain / gain : 1.0;
}

// A solver's relaxation 'relaxation', of gain 'gainPerUnit' (c above) per unit, held to the bound
// for this kernel on the lattice of spacing dx; says so in the log when the bound applies
// ("<what> relaxed by ...").
inline double boundedJacobiRelaxation(const KernelTable& kernel, double dx, int dimension, double relaxation,
                                      double gainPerUnit, const std::string& what) {
    const double gain = gainPerUnit * latticeMaxCorrectionGain(kernel, dx, dimension);
    const double bounded = std::min(relaxation, maxJacobiCorrectionGain / gain);
    if (bounded < relaxation) {
        std::ostringstream m;
        m << what << " relaxed by " << bounded << " instead of " << relaxation
          << ": the kernel's largest lattice correction gain times the solver's (" << gain << ") would exceed "
          << maxJacobiCorrectionGain;
        log::info(m.str());
    }
    return bounded;
}

// PCISPH's δ = −1 / (β (−Σ∇W_ij·Σ∇W_ij − Σ ∇W_ij·∇W_ij)), β = 2 Δt² m² / ρ0² (eq. 8), so that
// the pressure correction p̃_i = δ ρ*_err,i.
inline double pcisphDelta(const LatticeGradientSums& s, double dt, double mass, double rho0) {
    const double beta = 2 * dt * dt * mass * mass / (rho0 * rho0);
    return -1.0 / (beta * (-s.gradSumSquared - s.sumGradSquared));
}

} // namespace spindrift
