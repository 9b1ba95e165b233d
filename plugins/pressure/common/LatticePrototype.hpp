// Kernel-gradient sums of a prototype particle with a full neighbourhood on the case's initial
// lattice (spacing Δx, dimension 2 or 3): the particle at the origin, neighbours at (i, j, k)·Δx
// with 0 < r < h. Used by PCISPH's pressure scaling δ (Solenthaler & Pajarola 2009, eq. 8;
// MODELS.md "pcisph") and by the position-based solvers to make their relaxation parameters
// resolution-independent.
#pragma once

#include "KernelTable.hpp"

#include <cmath>

namespace spindrift {

struct LatticeGradientSums {
    double gradSumSquared = 0;  // Σ_j ∇W_ij · Σ_j ∇W_ij  (0 on a symmetric lattice)
    double sumGradSquared = 0;  // Σ_j ∇W_ij · ∇W_ij
    int neighbours = 0;         // lattice points with 0 < r < h
};

inline LatticeGradientSums latticeGradientSums(const KernelTable& kernel, double dx, int dimension) {
    const double h = kernel.supportRadius();
    const int reach = int(std::ceil(h / dx));
    LatticeGradientSums s;
    Vec3 sum = Vec3::Zero();
    for (int k = (dimension == 3 ? -reach : 0); k <= (dimension == 3 ? reach : 0); ++k)
        for (int j = -reach; j <= reach; ++j)
            for (int i = -reach; i <= reach; ++i) {
                if (i == 0 && j == 0 && k == 0) continue;
                // r_ij = x_i − x_j with x_i at the origin
                const Vec3 rij(Scalar(-i * dx), Scalar(-j * dx), Scalar(-k * dx));
                const Scalar r = rij.norm();
                if (r >= h) continue;
                const Vec3 g = kernel.gradW(rij, r);
                sum += g;
                s.sumGradSquared += double(g.squaredNorm());
                ++s.neighbours;
            }
    s.gradSumSquared = double(sum.squaredNorm());
    return s;
}

// PCISPH's δ = −1 / (β (−Σ∇W_ij·Σ∇W_ij − Σ ∇W_ij·∇W_ij)), β = 2 Δt² m² / ρ0² (eq. 8), so that
// the pressure correction p̃_i = δ ρ*_err,i.
inline double pcisphDelta(const LatticeGradientSums& s, double dt, double mass, double rho0) {
    const double beta = 2 * dt * dt * mass * mass / (rho0 * rho0);
    return -1.0 / (beta * (-s.gradSumSquared - s.sumGradSquared));
}

} // namespace spindrift
