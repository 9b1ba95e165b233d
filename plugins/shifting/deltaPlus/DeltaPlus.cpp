// deltaPlus — the particle shifting of δ⁺-SPH, Sun, Colagrossi, Marrone & Zhang (2017), Comput.
// Methods Appl. Mech. Engrg. 315, 25–49, doi:10.1016/j.cma.2016.10.028, with the free-surface
// detection of Marrone et al. (2010), J. Comput. Phys. 229(10), 3652–3663,
// doi:10.1016/j.jcp.2010.01.019; docs/MODELS.md §deltaPlus.
//
// Particles move with v + δv, δv down the gradient of the particle concentration, with
// Monaghan's anti-clustering weight on close pairs (paper eq. 7, written as a velocity, δr = Δt δv):
//   δv_i = −U h²/(2Δx) [Σ_j (1 + R (W_ij/W(Δx))ⁿ) m/(ρ_i + ρ_j) ∇_i W_ij
//                      + Σ_b (1 + R (W_ib/W(Δx))ⁿ) M_b/(ρ_i + ρ_b) ∇_i W_ib]
// h the support radius (= 2h_s for kernels of support 2h_s, so h² is the paper's (2h_s)²), U the
// largest fluid speed (or `maxVelocity`), R = 0.2, n = 4. The paper's CFL·Ma (= Δt U/h_s) is
// replaced by Δt U/(2Δx), as TrixiParticles does (the same at h_s = 2Δx; it keeps the shift
// when h/Δx changes). Wall particles (M_b, ρ_b of the boundary model) count in every sum, so
// fluid is not drawn into a wall; walls are never shifted.
// Free surface: the renormalisation matrix B_i = −Σ_j V_j r_ij ⊗ ∇_i W_ij (walls included,
// V = m/ρ), whose smallest eigenvalue λ_i is ≈ 1 inside the fluid and ≈ 0.5 on a flat surface,
// and the outward normal n_i = −B_i⁻¹ Σ_j V_j ∇_i W_ij / |…| (the renormalised gradient of the
// colour function). Then
//   λ_i < 0.4                                δv_i = 0                    (splashes, lone particles)
//   λ_i < 0.75 (surface)                     δv_i ← (I − n_i n_i) δv_i   (along the surface only)
//   a surface particle within the support    δv_i ← (I − n_s n_s) δv_i   (n_s of the nearest one)
//   otherwise                                δv_i unchanged
// so no particle is pushed out through the surface (which plain shifting does: the concentration
// falls off there). |Δt δv_i| is capped at maxShift·Δx; the log says when the cap acts.
// Shifting moves particles, not their values: quantities are not corrected to the new position
// (as in the paper), and with continuity density the shift is not seen by the density.
//
//   shifting
//   {
//       type            deltaPlus;
//       maxVelocity     2;       // U [m/s]; default: the largest fluid speed at each evaluation
//       R               0.2;     // anti-clustering weight
//       n               4;       // its exponent
//       maxShift        0.1;     // largest shift a step, in particle spacings Δx (0: no cap)
//       freeSurface     yes;     // the surface treatment (no: shift everywhere, internal flows)
//   }
#include "KernelCorrection.hpp" // MomentAndColour, smallestEigenvalue
#include "Log.hpp"
#include "PairLoop.hpp"
#include "Plugin.hpp"
#include "ShiftingModel.hpp"

#include <cmath>
#include <limits>
#include <sstream>

namespace {
using namespace spindrift;

// Σ (1 + R (W/W(Δx))ⁿ) M/(ρ_i + ρ_j) ∇W, and for the surface: −Σ V r ⊗ ∇W and Σ V ∇W.
struct ShiftTerm {
    struct Sum {
        Vec3 shift = Vec3::Zero();
        MomentAndColour surface;
    };
    static constexpr bool usesGradient = true, usesKernel = true;
    using Particle = Scalar; // ρ_i
    const Scalar* rho;
    Scalar m, R, invWdx;
    int n;
    bool surface;
    Particle particle(std::size_t i) const { return rho[i]; }
    Scalar weight(Scalar W) const { return 1 + R * std::pow(W * invWdx, Scalar(n)); }
    void add(Scalar rhoi, Scalar mass, Scalar rhoj, const Pair& q, Sum& sum) const {
        sum.shift += (weight(q.W) * mass / (rhoi + rhoj)) * q.gradW;
        if (surface) sum.surface.add(mass / rhoj, q);
    }
    void fluid(Scalar rhoi, const Pair& q, Sum& sum) const { add(rhoi, m, rho[q.j], q, sum); }
    void wall(Scalar rhoi, const WallPair& q, Sum& sum) const {
        add(rhoi, q.mass(), q.src.mirrored ? rhoi : q.src.rho[q.j], q, sum);
    }
};

// The nearest fluid neighbour on the surface (index, r²), for the particles beside the surface.
struct NearestSurfaceTerm {
    struct Sum {
        Index j = std::numeric_limits<Index>::max();
        Scalar r2 = std::numeric_limits<Scalar>::max();
    };
    struct Particle {};
    const signed char* zone;
    Particle particle(std::size_t) const { return {}; }
    void fluid(const Particle&, const Pair& q, Sum& sum) const {
        if (zone[q.j] == surfaceZone && q.r2 < sum.r2) sum = {q.j, q.r2};
    }
    static constexpr signed char surfaceZone = 1;
};

class DeltaPlus final : public ShiftingModel {
public:
    explicit DeltaPlus(const ModelContext& c)
        : maxVelocity_(c.dict.getOrDefault<double>("maxVelocity", 0.0)),
          R_(c.dict.getOrDefault<double>("R", 0.2)), n_(c.dict.getOrDefault<int>("n", 4)),
          maxShift_(c.dict.getOrDefault<double>("maxShift", 0.1)),
          freeSurface_(c.dict.getOrDefault<bool>("freeSurface", true)) {
        if (!(maxVelocity_ >= 0))
            throw InputError(c.dict.locationOf("maxVelocity"), "maxVelocity must not be negative", "maxVelocity");
        if (!(R_ >= 0)) throw InputError(c.dict.locationOf("R"), "R must not be negative", "R");
        if (n_ < 1) throw InputError(c.dict.locationOf("n"), "n must be a positive whole number", "n");
        if (!(maxShift_ >= 0))
            throw InputError(c.dict.locationOf("maxShift"), "maxShift must not be negative (0: no cap)", "maxShift");
    }

    void initialise(Scene& s) override {
        for (ParticleSystem* fluid : s.ofRole(SystemRole::fluid)) {
            // the zone of each particle (0 bulk, 1 surface, 2 beside it, −1 not shifted), written
            // when named in writeFields
            fluid->particles.addScalar("shiftingZone", {false, false});
            fluid->particles.addVector("surfaceNormal", {false, false, true});
        }
        const Scalar Wdx = s.kernel.W(s.physics.particleSpacing);
        invWdx_ = Wdx > 0 ? 1 / Wdx : 0;
    }

    void computeShift(Scene& s, ParticleSystem& fluid, const Step& step) override {
        const Scalar dt = step.dt;
        auto& shift = *fluid.particles.findVector("shiftingVelocity"); // (the core's field)
        auto& zone = *fluid.particles.findScalar("shiftingZone");
        auto& normal = *fluid.particles.findVector("surfaceNormal");
        const std::size_t count = fluid.size();
        const auto& x = fluid.particles.position();
        const auto& v = fluid.particles.velocity();
        const Scalar U = maxVelocity_ > 0
                             ? maxVelocity_
                             : Scalar(std::sqrt(parallelMax(count, [&](std::size_t i) { return v[i].squaredNorm(); })));
        const Scalar h = s.constants.supportRadius, dx = s.physics.particleSpacing;
        const Scalar scale = -U * h * h / (2 * dx);
        const int d = s.physics.dimension;
        const bool surface = freeSurface_;
        zoneCode_.assign(count, 0);
        const ShiftTerm term{fluid.particles.density().data(), fluid.particles.particleMass(), R_, invWdx_, n_, surface};
        forEachPairSum(s, fluid, x, term, [&](std::size_t i, Scalar, const ShiftTerm::Sum& sum) {
            shift[i] = scale * sum.shift;
            if (!surface) return;
            const Scalar lambda = smallestEigenvalue(sum.surface.moment, d);
            normal[i] = sum.surface.outwardNormal(d);
            zoneCode_[i] = lambda < Scalar(0.4) ? splashZone : lambda < Scalar(0.75) ? NearestSurfaceTerm::surfaceZone : 0;
        });
        bool anySurface = false;
        for (signed char z : zoneCode_) anySurface |= z == NearestSurfaceTerm::surfaceZone;
        nearestSurface_.assign(count, none);
        if (anySurface)
            forEachPairSum(s, fluid, x, NearestSurfaceTerm{zoneCode_.data()},
                           [&](std::size_t i, const auto&, const NearestSurfaceTerm::Sum& nearest) {
                               if (zoneCode_[i] == 0 && nearest.r2 < h * h) nearestSurface_[i] = nearest.j;
                           });
        // the surface treatment and the cap
        const Scalar cap = maxShift_ > 0 && dt > 0 ? maxShift_ * dx / dt : std::numeric_limits<Scalar>::infinity();
        clipped_.assign(count, 0);
        forEachIndex(count, [&](std::size_t i) {
            Vec3 dv = shift[i];
            signed char z = zoneCode_[i];
            if (z == splashZone) dv.setZero();
            else if (z == NearestSurfaceTerm::surfaceZone) dv -= dv.dot(normal[i]) * normal[i];
            else if (nearestSurface_[i] != none) {
                const Vec3& ns = normal[nearestSurface_[i]];
                dv -= dv.dot(ns) * ns;
                z = besideZone;
            }
            const Scalar speed = dv.norm();
            if (speed > cap) {
                dv *= cap / speed;
                clipped_[i] = 1;
            }
            shift[i] = dv;
            zone[i] = z;
        });
        reportClipping(s, long(deterministicSum(count, [&](std::size_t i) { return double(clipped_[i]); })));
    }

    // it only shifts (adds no acceleration): no force on a wall or body
    void addReactions(const Scene&, const ParticleSystem&, const Step&, Reactions&) const override {}

private:
    static constexpr signed char splashZone = -1, besideZone = 2;
    static constexpr Index none = std::numeric_limits<Index>::max();

    // a warning the first time the cap acts, then whenever the number of steps with clipping
    // reaches a power of ten
    void reportClipping(const Scene& s, long clipped) {
        if (clipped == 0) return;
        ++clippedSteps_;
        clippedParticles_ += clipped;
        if (clippedSteps_ < nextReport_) return;
        nextReport_ *= 10;
        std::ostringstream m;
        m << "shifting deltaPlus: the shift of " << clipped << " particles was capped at " << maxShift_
          << " dx at step " << s.step << " (" << clippedSteps_ << " steps with capped shifts so far, "
          << clippedParticles_ << " particle-steps)";
        log::warning(m.str());
    }

    Scalar maxVelocity_, R_;
    int n_;
    Scalar maxShift_;
    bool freeSurface_;
    Scalar invWdx_ = 0;
    std::vector<signed char> zoneCode_;
    std::vector<char> clipped_; // whether the cap clipped a particle's shift (scratch of a call)
    std::vector<Index> nearestSurface_; // beside the surface: the nearest surface particle
    long clippedSteps_ = 0, clippedParticles_ = 0, nextReport_ = 1;
};
} // namespace

SPINDRIFT_PLUGIN(ShiftingModel, DeltaPlus)
