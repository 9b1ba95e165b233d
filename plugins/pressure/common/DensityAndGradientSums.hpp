// Pair terms shared by the implicit solvers that cache ∇W_ij once per neighbour search and
// stream it through their iterations (dfsph, iisph; libsrc/PairLoop.hpp's forEachPairSum and
// forEachCachedPairSum).
#pragma once

#include "KernelCorrection.hpp"
#include "PairLoop.hpp"
#include "Step.hpp"

namespace spindrift {

// ρ_i's kernel sums and the gradient sums the solvers' diagonals and wall terms need, at the
// step's positions; every fluid pair's ∇W_ij goes to the scene's cache (by its place k in the
// lists). ρ_i = m (W(0) + w) + wall.
struct DensityAndGradientSumsTerm {
    struct Sum {
        Scalar w = 0, squares = 0, wall = 0, wallRate = 0; // Σ W_ij, Σ |∇W_ij|², Σ M_b W_ib, Σ M_b v_b·∇W_ib (moving walls)
        Vec3 grad = Vec3::Zero();                          // Σ ∇W_ij
        Vec3 wallGrad = Vec3::Zero(), mirroredGrad = Vec3::Zero(); // Σ M_b ∇W_ib, over the walls that mirror p
    };
    static constexpr bool usesGradient = true, usesKernel = true;
    struct Particle {};
    Vec3* gradients;
    Particle particle(std::size_t) const { return {}; }
    void fluid(const Particle&, const Pair& q, Sum& sum) const {
        sum.w += q.W;
        gradients[q.k] = q.gradW;
        sum.grad += q.gradW;
        sum.squares += q.gradW.squaredNorm();
    }
    void wall(const Particle&, const WallPair& q, Sum& sum) const {
        sum.wall += q.mass() * q.W;
        const Vec3 g = q.mass() * q.gradW;
        sum.wallGrad += g;
        if (q.src.mirrored) sum.mirroredGrad += g;
        if (q.src.moving) sum.wallRate += q.src.v[q.j].dot(g);
    }
};

// out(i, sum) with DensityAndGradientSumsTerm's sums of every particle i of the fluid at
// positions x, on the lists of the search's last build (which must be at x); the pair gradients
// fill the fluid's cache, valid from then on for those lists (the density pass of pcisph, iisph
// and dfsph).
template <class Out> void densityAndGradientSums(Scene& s, ParticleSystem& fluid, const std::vector<Vec3>& x, Out&& out) {
    const QueryLists& q = s.listsOf(fluid);
    fluid.gradients.values.resize(q.own().totalPairs());
    fluid.gradients.invalidate();
    forEachPairSum(s, fluid, x, DensityAndGradientSumsTerm{fluid.gradients.values.data()},
                   [&](std::size_t i, const auto&, const DensityAndGradientSumsTerm::Sum& sum) { out(i, sum); });
    fluid.gradients.stamp = q.stamp();
}

// Σ_j (u_i − u_j)·∇W_ij over the fluid pairs, for any per-particle vector u (a velocity: the
// fluid part of Dρ_i/Dt over m; an acceleration: that of a displacement over Δt²), with the
// cached gradients (forEachCachedPairSum; DensityAndGradientSumsTerm's sums give the walls'
// part: u_i·wallGrad − wallRate).
struct FluidDivergenceTerm {
    using Sum = Scalar;
    using Particle = Vec3; // u_i
    const Vec3* u;
    Particle particle(std::size_t i) const { return u[i]; }
    void cached(const Vec3& ui, Index j, const Vec3& gradW, Sum& sum) const { sum += (ui - u[j]).dot(gradW); }
};

// Σ_b M_b p_b/ρ_b² ∇W_ib over the boundaries with a pressure of their own (adami: extrapolated
// from the fluid's), the boundaries alone: their push, which iisph and dfsph take again whenever
// the core has carried a new fluid pressure to them (StepServices::updateBoundaryPressure).
struct OwnWallPressureTerm {
    using Sum = Vec3;
    static constexpr bool usesGradient = true;
    static constexpr bool visitsFluid = false;
    struct Particle {};
    Particle particle(std::size_t) const { return {}; }
    void wall(const Particle&, const WallPair& q, Sum& sum) const {
        if (q.src.mirrored) return;
        const Scalar rho = q.src.rho[q.j];
        sum += (q.mass() * q.src.p[q.j] / (rho * rho)) * q.gradW;
    }
};

// The push of boundaries of their own pressure (adami) on a fluid whose pressure changes within
// a solve (dfsph, pbf, relaxedPbf), taken in increments: update() has the core carry the fluid's
// pressure p so far to the boundaries (StepServices::updateBoundaryPressure) and gives apply(i, Δ)
// the change Δ of Σ_b M_b p_b/ρ_b² ∇W_ib at positions x since the last update of this solve, so
// that over the solve the boundaries push with the pressure the fluid ends with.
class OwnWallPush {
public:
    void start(std::size_t n) { applied_.assign(n, Vec3::Zero()); }
    // (L: each particle's kernel correction L_i, which then multiplies its push: gradientCorrection)
    template <class Apply>
    void update(Scene& s, const ParticleSystem& fluid, const Step& step, const std::vector<Scalar>& p,
                const std::vector<Vec3>& x, Apply&& apply, const Mat3* L = nullptr) {
        step.core.updateBoundaryPressure(s, fluid, p);
        forEachPairSum(s, fluid, x, OwnWallPressureTerm{}, [&](std::size_t i, const auto&, const Vec3& sum) {
            const Vec3 push = L ? Vec3(L[i] * sum) : sum;
            apply(i, Vec3(push - applied_[i]));
            applied_[i] = push;
        });
    }

private:
    std::vector<Vec3> applied_; // Σ_b M_b p_b/ρ_b² ∇W_ib as applied so far
};

// Σ_j (s_i + s_j) ∇W_ij over the cached gradients, for any per-particle scalar s (p/ρ²: the
// symmetric pressure gradient over m; dfsph's κ/ρ: its stiffness step).
struct CachedSymmetricGradientTerm {
    using Sum = Vec3;
    using Particle = Scalar; // s_i
    const Scalar* s;
    Particle particle(std::size_t i) const { return s[i]; }
    void cached(Scalar si, Index j, const Vec3& gradW, Sum& sum) const { sum += (si + s[j]) * gradW; }
};

} // namespace spindrift
