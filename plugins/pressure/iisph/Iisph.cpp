// iisph — implicit incompressible SPH (Ihmsen, Cornelis, Solenthaler, Horvath & Teschner 2014,
// "Implicit Incompressible SPH", IEEE TVCG 20(3) 426–435, doi:10.1109/TVCG.2013.105;
// docs/MODELS.md §iisph). The pressure that makes the density predicted for the end of the step ρ0 solves a
// linear system (a discrete pressure Poisson equation), by relaxed Jacobi, on the step's
// neighbour lists, linearised about the step's positions (as DFSPH: no re-search):
//   v_adv = v + Δt a_nonp                                              (advection)
//   ρ_adv,i = ρ_i + Δt [Σ_j m (v_adv,i − v_adv,j)·∇W_ij + Σ_b M_b (v_adv,i − v_b)·∇W_ib]
//   Δx_i = Δt² a_p,i = d_ii p_i + Σ_j d_ij p_j (+ e_i)                 (displacement by pressure)
//     d_ii = −Δt²/ρ_i² (Σ_j m ∇W_ij + Σ_b (1 + μ_b) M_b ∇W_ib),  d_ij = −Δt² m/ρ_j² ∇W_ij,
//     e_i = −Δt² Σ_b (1 − μ_b) M_b p_b/ρ_b² ∇W_ib
//   ρ*_i = ρ_adv,i + Σ_j m (Δx_i − Δx_j)·∇W_ij + Σ_b M_b Δx_i·∇W_ib  =  ρ_adv,i + a_ii p_i + s_i
//     a_ii = Σ_j m (d_ii − d_ji)·∇W_ij + Σ_b M_b d_ii·∇W_ib
//          = −Δt²/ρ_i² [(Σ_j m ∇W_ij + Σ_b (1 + μ_b) M_b ∇W_ib)·(Σ_j m ∇W_ij + Σ_b M_b ∇W_ib) + m² Σ_j |∇W_ij|²]
//   p_i ← max(0, (1 − ω) p_i + ω (ρ0 − ρ_adv,i − s_i)/a_ii)  =  max(0, p_i + ω (ρ0 − ρ*_i)/a_ii)
// (ω: omega, 0.5 as the paper, held to at most 0.9/g, g the kernel's largest lattice correction
// gain, boundedJacobiRelaxation in LatticePrototype.hpp, as ω/a_ii is twice pcisph's δ: with the
// Wendland C2 at 4Δx in 2D, g = 2.84, an unbounded ω = 0.5 blew up at the Colagrossi dam break's
// corner)
//   a_p,i = −Σ_j m (p_i/ρ_i² + p_j/ρ_j²) ∇W_ij − Σ_b M_b (p_i/ρ_i² + q_b) ∇W_ib        (returned)
// (μ_b = 1 on a wall that mirrors the fluid's pressure, q_b = p_i/ρ_i²: the boundary model's
// Akinci walls; μ_b = 0 on a wall with its own pressure and density, q_b = p_b/ρ_b², constant
// within the solve). s_i is the paper's Σ_j m (Σ_k d_ik p_k − d_jj p_j − Σ_{k≠i} d_jk p_k)·∇W_ij
// (with the walls' and e's terms); it is not summed in that form: each iteration takes two
// passes over the fluid pairs, the displacements Δx_i = Δt² a_p,i of the current p (the
// paper's first loop, Σ_j d_ij p_j, with d_ii p_i and the wall terms added), then ρ*_i, which
// is ρ_adv,i + a_ii p_i + s_i exactly (the paper's second loop). So the linear system and the
// returned acceleration are one wall model, derived once: a mirrored wall's force acts with
// 2 p_i/ρ_i², as in SymmetricPressureTerm, and d_ii and a_ii carry the same factor (a system
// that disagrees with the force applied converges to a wrong pressure at the wall). The
// pressure is in Pa (SPlisHSPlasH's normalised units hold p/ρ0).
// The solve stops when the density error of ρ* (the compression max(0, ρ*_i − ρ0)/ρ0, its
// average over the particles by default) is at most η after at least minIterations
// corrections (sphSolution `pressure { }`, IterativeSolverControls); the check comes before
// each correction, so the acceleration returned is that of the pressure whose ρ* met η.
// ρ_i, Σ_j ∇W_ij, Σ_j |∇W_ij|² and the wall sums are taken with the density, after the
// neighbour search, and every fluid pair's ∇W_ij goes to the scene's gradient cache, which the
// solve's passes stream (forEachCachedPairSum; the viscosity reads it too); the walls need no
// pass in the solve (walls with their own pressure: one a step, for e_i). The cache pays: on the
// speed benchmark's cube (3 iterations a step) a step took 0.56 (1 thread) and 0.51 (2 threads)
// of the time of the same solve evaluating ∇W from the kernel table in every pass (paired
// rounds, Allrun -compare), for 17 % more memory (1,080 against 919 bytes a particle).
// The pressure warm-starts from warmStart × the last step's (fluid.pressure() is a restart
// field: restarts continue bit for bit); below zero it is clamped to 0 (free surfaces:
// particles with ρ* < ρ0 pull on nothing), as is that of a particle without neighbours.
// The model returns a_nonp + a_p (ResultKind::acceleration): with symplectic Euler the step takes
// exactly the predicted velocities, up to the linearisation (the real density after the step
// differs from ρ* by O(Δt²)).
//
//   pressure { type iisph; omega 0.5; warmStart 0.5; }
//   sphSolution: pressure { maxDensityError 0.001; densityErrorNorm average; minIterations 2;
//                           maxIterations 100; }
#include "DensityAndGradientSums.hpp"
#include "IterativeSolverControls.hpp"
#include "LatticePrototype.hpp"
#include "Plugin.hpp"
#include "PairLoop.hpp"
#include "PressureModel.hpp"

#include <stdexcept>

namespace {
using namespace spindrift;

// The solve's terms, over the cached gradients.
// Σ_j (v_i − v_j)·∇W_ij and Σ_j (q_i + q_j) ∇W_ij: the advected density and the first
// displacements in one pass.
struct AdvectionAndPressureTerm {
    struct Sum {
        Scalar rate = 0;
        Vec3 push = Vec3::Zero();
    };
    struct Particle {
        Vec3 v;
        Scalar q;
    };
    const Vec3* v;
    const Scalar* q;
    Particle particle(std::size_t i) const { return {v[i], q[i]}; }
    void cached(const Particle& pi, Index j, const Vec3& gradW, Sum& sum) const {
        sum.rate += (pi.v - v[j]).dot(gradW);
        sum.push += (pi.q + q[j]) * gradW;
    }
};

class Iisph final : public PressureModel {
public:
    explicit Iisph(const ModelContext& c)
        : rho0_(c.physics.rho0), omega_(c.dict.getOrDefault<double>("omega", 0.5)),
          warmStart_(c.dict.getOrDefault<double>("warmStart", 0.5)) {
        if (!(omega_ > 0 && omega_ <= 1))
            throw InputError(c.dict.locationOf("omega"), "omega (the Jacobi relaxation) must be in (0, 1]", "omega");
        if (!(warmStart_ >= 0 && warmStart_ <= 1))
            throw InputError(c.dict.locationOf("warmStart"), "warmStart must be in [0, 1]", "warmStart");
        controls_ = {Scalar(0.001), IterativeSolverControls::Norm::Average, 2, 100}; // as dfsph: 0.1 % of the average
        controls_.read(c.solution);
    }

    void initialise(Scene& s) override {
        relaxation_ = Scalar(boundedJacobiRelaxation(s.kernel, s.physics.particleSpacing, s.physics.dimension, omega_,
                                                     2, "iisph: the Jacobi iteration"));
        for (ParticleSystem* fluid : s.ofRole(SystemRole::fluid)) {
            auto& set = fluid->particles;
            for (const char* name : {"iisphDiagonal", "iisphInvRho2", "iisphWallRate"}) set.addScalar(name, scratch);
            for (const char* name : {"iisphWallGrad", "iisphPressureWallGrad"}) set.addVector(name, scratch);
        }
    }

    void computeDensity(Scene& s, ParticleSystem& fluid, const Step&) override {
        const auto& x = fluid.particles.position();
        const Scalar m = fluid.particles.particleMass(), w0 = s.kernel.W0(), h = s.constants.supportRadius;
        // a_ii's bracket below this (no neighbours) leaves the particle's pressure at zero
        const Scalar tiny = Scalar(1e-9) * rho0_ * rho0_ / (h * h);
        auto& rho = fluid.particles.density();
        const Factors f = factorsOf(fluid);
        densityAndGradientSums(s, fluid, x, [&](std::size_t i, const DensityAndGradientSumsTerm::Sum& sum) {
            const Scalar r = m * (w0 + sum.w) + sum.wall;
            rho[i] = r;
            f.invRho2[i] = 1 / (r * r);
            const Vec3 fluidGrad = m * sum.grad;
            const Vec3 pressureGrad = sum.wallGrad + sum.mirroredGrad; // Σ_b (1 + μ_b) M_b ∇W_ib
            f.wallGrad[i] = sum.wallGrad;
            f.pressureWallGrad[i] = pressureGrad;
            f.wallRate[i] = sum.wallRate;
            const Scalar bracket = (fluidGrad + pressureGrad).dot(fluidGrad + sum.wallGrad) + m * m * sum.squares;
            f.diagonal[i] = bracket > tiny ? r * r / bracket : Scalar(0); // −Δt²/a_ii
        });
    }

    void addPressureAcceleration(Scene& s, ParticleSystem& fluid, const Step& step) override {
        const Scalar dt = step.dt;
        const std::size_t n = fluid.size();
        const auto& v = fluid.particles.velocity();
        const auto& rho = fluid.particles.density();
        auto& a = fluid.particles.acceleration();
        auto& p = fluid.particles.pressure();
        if (!fluid.gradients.validFor(s.listsOf(fluid)))
            throw std::logic_error("iisph: computeDensity must run after each neighbour search (it caches the gradients)");
        const Factors f = factorsOf(fluid);
        advected_.resize(n);
        q_.resize(n);
        qNext_.resize(n);
        pNext_.resize(n);
        pressureAcceleration_.resize(n);
        rhoAdvected_.resize(n);
        rhoPredicted_.resize(n);
        const Scalar m = fluid.particles.particleMass(), dt2 = dt * dt, invDt2 = 1 / dt2, w = warmStart_;
        forEachIndex(n, [&](std::size_t i) {
            advected_[i] = v[i] + dt * a[i];
            p[i] = f.diagonal[i] > 0 ? w * p[i] : Scalar(0);
            q_[i] = p[i] * f.invRho2[i];
        });
        // the walls with their own pressure (adami: extrapolated from the fluid's) follow the
        // fluid's pressure at every iteration, as in pcisph; within an iteration their force is
        // constant (a_ii leaves out the wall's dependence on p_i)
        const bool ownPressureWalls = step.core.boundariesHaveOwnPressure(s);
        const auto pushOfOwnPressureWalls = [&] {
            if (!ownPressureWalls) return;
            step.core.updateBoundaryPressure(s, fluid, p);
            ownWallPush_.resize(n);
            forEachPairSum(s, fluid, fluid.particles.position(), OwnWallPressureTerm{},
                           [&](std::size_t i, const auto&, const Vec3& sum) { ownWallPush_[i] = sum; });
        };
        pushOfOwnPressureWalls();
        // a_p,i (= Δx_i/Δt²) of the pressure q = p/ρ², given Σ_j (q_i + q_j) ∇W_ij
        const auto setPressureAcceleration = [&](std::size_t i, Scalar qi, const Vec3& push) {
            Vec3 force = m * push + qi * f.pressureWallGrad[i];
            if (ownPressureWalls) force += ownWallPush_[i];
            pressureAcceleration_[i] = -force;
        };
        forEachCachedPairSum(s, fluid, AdvectionAndPressureTerm{advected_.data(), q_.data()},
                             [&](std::size_t i, const auto& pi, const AdvectionAndPressureTerm::Sum& sum) {
                                 rhoAdvected_[i] = rho[i] + dt * (m * sum.rate + pi.v.dot(f.wallGrad[i]) - f.wallRate[i]);
                                 setPressureAcceleration(i, pi.q, sum.push);
                             });

        const Scalar relax = relaxation_ * invDt2, rho0 = rho0_;
        int iterations = 0;
        CompressionError err;
        for (;;) {
            // ρ* of the current pressure, and the next pressure (taken if ρ* misses η)
            forEachCachedPairSum(s, fluid, FluidDivergenceTerm{pressureAcceleration_.data()},
                                 [&](std::size_t i, const Vec3& ai, Scalar sum) {
                                     const Scalar predicted = rhoAdvected_[i] + dt2 * (m * sum + ai.dot(f.wallGrad[i]));
                                     rhoPredicted_[i] = predicted;
                                     const Scalar next = std::max(p[i] + relax * f.diagonal[i] * (predicted - rho0), Scalar(0));
                                     pNext_[i] = next;
                                     qNext_[i] = next * f.invRho2[i];
                                 });
            err = compressionError(rhoPredicted_, rho0);
            if (controls_.done(iterations, err.max, err.avg)) break;
            p.swap(pNext_);
            q_.swap(qNext_);
            pushOfOwnPressureWalls();
            forEachCachedPairSum(s, fluid, CachedSymmetricGradientTerm{q_.data()},
                                 [&](std::size_t i, Scalar qi, const Vec3& push) { setPressureAcceleration(i, qi, push); });
            ++iterations;
        }
        forEachIndex(n, [&](std::size_t i) { a[i] += pressureAcceleration_[i]; });
        stats_ = {iterations, controls_.converged(err.max, err.avg), err.max, err.avg};
    }

    // the final pressure's: a_ib = −M_b (q_i + q_b) ∇W_ib, q_b = q_i on a mirroring wall
    void addReactions(const Scene& s, const ParticleSystem& fluid, const Step&, Reactions& r) const override {
        addSymmetricPressureReactions(s, fluid, fluid.particles.position(), q_.data(), r);
    }

    bool isIterative() const override { return true; }
    double maxTimeStep(const Scene& s, const StateSpeeds& v) const override { return controls_.maxTimeStep(s, v); }
    SolverStats lastSolve() const override { return stats_; }

private:
    static constexpr FieldOptions scratch{false, false, true};
    // per particle, from the density pass (scratch fields of each fluid): ρ_i²/(a_ii's bracket)
    // = −Δt²/a_ii (0: no neighbours), 1/ρ_i², Σ_b M_b ∇W_ib, Σ_b (1 + μ_b) M_b ∇W_ib,
    // Σ_b M_b v_b·∇W_ib
    struct Factors {
        Scalar *diagonal, *invRho2, *wallRate;
        Vec3 *wallGrad, *pressureWallGrad;
    };
    static Factors factorsOf(ParticleSystem& fluid) {
        auto& set = fluid.particles;
        return {set.findScalar("iisphDiagonal")->data(), set.findScalar("iisphInvRho2")->data(),
                set.findScalar("iisphWallRate")->data(), set.findVector("iisphWallGrad")->data(),
                set.findVector("iisphPressureWallGrad")->data()};
    }

    Scalar rho0_, omega_, warmStart_;
    Scalar relaxation_ = 0.5; // omega held to the bound (boundedJacobiRelaxation, LatticePrototype.hpp)
    IterativeSolverControls controls_;
    // the solve's: v_adv, q = p/ρ² (and the next), the next p, a_p = Δx/Δt², ρ_adv, ρ*, Σ_b M_b q_b ∇W_ib
    std::vector<Vec3> advected_;
    std::vector<Scalar> q_, qNext_, pNext_;
    std::vector<Vec3> pressureAcceleration_, ownWallPush_;
    std::vector<Scalar> rhoAdvected_, rhoPredicted_;
    SolverStats stats_;
};
} // namespace

SPINDRIFT_PLUGIN(PressureModel, Iisph)
