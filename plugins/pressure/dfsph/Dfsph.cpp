// dfsph — divergence-free SPH (Bender & Koschier 2015, "Divergence-Free Smoothed Particle
// Hydrodynamics", SCA; 2017 TVCG, Alg. 1–3), the incompressible solver SPlisHSPlasH defaults
// to. Two Jacobi solves on the step's neighbour lists, both on velocities (no prediction of
// positions, no second neighbour search unless checkPositions), with a per-particle factor
//   α_i = ρ_i / (|Σ_j m ∇W_ij + Σ_b M_b ∇W_ib|² + Σ_j |m ∇W_ij|²)                 (eq. 8)
// and the rate of density change Dρ_i/Dt = Σ_j m (v_i − v_j)·∇W_ij + Σ_b M_b v_i·∇W_ib (walls at rest).
// A stiffness κ_i (= p_i/ρ_i) changes the velocities by
//   v_i −= Δt [Σ_j m (κ_i/ρ_i + κ_j/ρ_j) ∇W_ij + Σ_b M_b (κ_i/ρ_i + p_b/ρ_b²) ∇W_ib]
// with p_b the pressure of a boundary of its own pressure (adami), which the boundary model
// extrapolates from the fluid's pressure of the step so far, p = ρ(κ + κ^v), after every
// correction (Adami, Hu & Adams 2012, eq. 27, hydrostatic term included; carried into DFSPH as
// Band et al. 2018 carry boundary pressure into IISPH: "Pressure boundaries for implicit
// incompressible SPH", ACM Trans. Graph. 37(2) 14, doi:10.1145/3180486). On a boundary that
// mirrors the fluid (akinci) p_b/ρ_b² is left out: the wall term once, as SPlisHSPlasH. Once on
// adami walls, the row beside a wall was pushed into it by its own κ through its fluid pairs and
// held only by the same κ once through the wall: it sank to 0.27Δx from the face (0.5Δx at rest)
// with an empty band above it, at twice the physical pressure (the hydrostatic tank's bottom
// probe +5.9 %, the Colagrossi far wall's P4 0.69 against 0.33 ρ0gH, issue 35).
//   1. divergence solve (Alg. 2, run here at the start of the step, after the neighbour
//      search, with the new ρ and α): κ_i = max(Dρ_i/Dt, 0) α_i / Δt until the average
//      Δt·Dρ/Dt/ρ0 ≤ maxDivergenceError; particles with few neighbours (free surface) are left
//      out, as in SPlisHSPlasH;
//   2. v* = v + Δt a_nonp;
//   3. density solve (Alg. 3): ρ*_i = ρ_i + Δt Dρ_i/Dt(v*), κ_i = max(ρ*_i − ρ0, 0) α_i / Δt²
//      until the density error (norm and η of sphSolution, as pcisph) is met. That error is the
//      linearised one; the real density at x + Δt v* is higher by O(Δt²) (at a splash of the
//      dam-break cube under CFL 2 % against η = 0.1 %). checkPositions (not in the paper)
//      searches and sums the density at x + Δt v* once the solve meets η and keeps the
//      difference δ_i in ρ*_i (δ warm-starts from the last step: field dfsphDensityOffset).
//      A check that meets η ends the solve and leaves its lists, density, α and gradients to
//      the next step, whose evaluation then skips the search (NeighbourSearch::buildAhead; over
//      a re-sort of the particles the core relabels the lists and the cached gradients, and this
//      model's scratch fields move with the particles), so a passed check costs no more than
//      the step it saves. A failed one
//      linearises again about the checked positions (their lists and factors;
//      ρ*_i = ρ_i(x + Δt v*) + Δt ΔDρ_i/Dt of the velocity change since) and the solve goes on
//      until a check meets η. In the dam-break cube under CFL: 1.08 checks and 1.08 searches a
//      step.
// The positions the solves linearise about do not change (but at a failed check), so ∇W of every
// fluid pair is computed once, with the density (computeDensity, after the neighbour search), and
// the solver passes (and the viscosity, through Scene::fluidPairGradients) only stream it;
// the walls' velocities do not change within a step, so their terms need only Σ_b M_b ∇W_ib and
// Σ_b M_b v_b·∇W_ib per particle, also computed once.
// Both solves' κ are relaxed by ω (omega, default 1: the paper's Jacobi), held to at most 0.9/g,
// g the kernel's largest lattice correction gain (boundedJacobiRelaxation, LatticePrototype.hpp:
// κ's update is twice pcisph's δ, so ω g ≤ 0.9 keeps every lattice wave's gain at most 1.8;
// 0.32 for the Wendland C2 at 4Δx in 2D, 0.64 for the cubic spline at 2Δx in 3D, near
// SPlisHSPlasH's 0.5). At ω g up to 1.8 (the bound on ω alone) the waves beyond the divergence
// limit were held only by the clamp ρ* ≥ ρ0 and rang a still column by ±70 % of its pressure
// and the Colagrossi far wall at H/80 (issue 35); without a bound the Colagrossi dam break blew
// up at its corner at H/40.
// Both solves warm-start from half of the last step's κ, scaled to this step's Δt (fields
// dfsphKappa, dfsphKappaV hold κ Δt² and κ_v Δt, as SPlisHSPlasH: restarts continue bit for bit). The model returns (v* − v)/Δt as its acceleration, so symplectic
// Euler gives v_{n+1} = v*, x_{n+1} = x_n + Δt v* (ResultKind::velocityChange). Wall particles b
// have the masses M_b the boundary model gives them.
//
//   pressure { type dfsph; omega 1; warmStart 0.5; divergenceSolve yes; checkPositions no; }
//   sphSolution: pressure { maxDensityError 0.001; densityErrorNorm average; minIterations 2;
//                           maxIterations 100; maxDivergenceError 0.001; maxDivergenceIterations 100; }
#include "DensityAndGradientSums.hpp"
#include "IterativeSolverControls.hpp"
#include "LatticePrototype.hpp"
#include "Log.hpp"
#include "Plugin.hpp"
#include "PairLoop.hpp"
#include "PressureModel.hpp"

#include <stdexcept>

namespace {
using namespace spindrift;

class Dfsph final : public PressureModel {
public:
    explicit Dfsph(const ModelContext& c)
        : rho0_(c.physics.rho0), warmStart_(c.dict.getOrDefault<double>("warmStart", 0.5)),
          omega_(c.dict.getOrDefault<double>("omega", 1.0)),
          divergenceSolve_(c.dict.getOrDefault<bool>("divergenceSolve", true)),
          checkPositions_(c.dict.getOrDefault<bool>("checkPositions", false)) {
        if (warmStart_ < 0 || warmStart_ > 1)
            throw InputError(c.dict.locationOf("warmStart"), "warmStart must be in [0, 1]", "warmStart");
        if (!(omega_ > 0 && omega_ <= 1))
            throw InputError(c.dict.locationOf("omega"), "omega (the Jacobi relaxation) must be in (0, 1]", "omega");
        if (c.solution) {
            maxDivergenceError_ = c.solution->getOrDefault<double>("maxDivergenceError", maxDivergenceError_);
            maxDivergenceIterations_ = c.solution->getOrDefault<int>("maxDivergenceIterations", maxDivergenceIterations_);
            if (!(maxDivergenceError_ >= 0))
                throw InputError(c.solution->locationOf("maxDivergenceError"), "maxDivergenceError must not be negative",
                                 "maxDivergenceError");
            if (maxDivergenceIterations_ < 1)
                throw InputError(c.solution->locationOf("maxDivergenceIterations"),
                                 "maxDivergenceIterations must be at least 1", "maxDivergenceIterations");
        }
        controls_ = {Scalar(0.001), IterativeSolverControls::Norm::Average, 2, 100}; // SPlisHSPlasH's defaults
        controls_.read(c.solution);
    }

    void initialise(Scene& s) override {
        for (ParticleSystem* fluid : s.ofRole(SystemRole::fluid)) {
            auto& set = fluid->particles;
            set.addScalar("dfsphKappa", {false, true});
            set.addScalar("dfsphKappaV", {false, true});
            if (checkPositions_) {
                set.addScalar("dfsphDensityOffset", {false, true});
                set.addScalar("dfsphNextDensity", scratch);
            }
            // kept from a passed check to the next step, so they move with the particles
            set.addScalar("dfsphAlphaOverRho", scratch);
            set.addVector("dfsphWallGradient", scratch);
            set.addScalar("dfsphWallRate", scratch);
        }
        minNeighbours_ = s.physics.dimension == 3 ? 20 : 7;
        relaxation_ = Scalar(boundedJacobiRelaxation(s.kernel, s.physics.particleSpacing, s.physics.dimension, omega_,
                                                     2, "dfsph: both solves"));
    }

    ResultKind result() const override { return ResultKind::velocityChange; }

    // ρ_i, α_i, the pair gradients and the wall sums at the current positions; taken over from
    // the last step's check when it searched at exactly these positions (the core then kept
    // that search, and the cached gradients are still valid).
    void computeDensity(Scene& s, ParticleSystem& fluid, const Step&) override {
        const Fields f = fieldsOf(fluid);
        const QueryLists& q = s.listsOf(fluid);
        char& passed = checkPassed(fluid);
        if (passed && s.search.builtAt(fluid.index, fluid.particles.position()) && fluid.gradients.validFor(q)) {
            fluid.particles.density().swap(*f.nextDensity);
            passed = 0;
            ++checksTaken_;
            return;
        }
        if (passed && ++checksNotTaken_ == 20 && checksTaken_ == 0)
            log::warning("dfsph: the positions of the step are never those checkPositions checked (x + deltaT v, "
                         "as symplecticEuler computes them): the check is approximate and costs a neighbour "
                         "search of its own each step");
        passed = 0;
        densityAndFactors(s, fluid, fluid.particles.position(), fluid.particles.density());
    }

    void addPressureAcceleration(Scene& s, ParticleSystem& fluid, const Step& step) override {
        const Scalar dt = step.dt;
        const std::size_t n = fluid.size();
        const auto& v = fluid.particles.velocity();
        const auto& rho = fluid.particles.density();
        auto& a = fluid.particles.acceleration();
        auto& p = fluid.particles.pressure();
        const QueryLists& lists = s.listsOf(fluid);
        if (!fluid.gradients.validFor(lists))
            throw std::logic_error("dfsph: computeDensity must run after each neighbour search (it caches the gradients)");
        const Fields f = fieldsOf(fluid);
        velocity_.resize(n);
        forEachIndex(n, [&](std::size_t i) { velocity_[i] = v[i]; });
        rate_.resize(n);
        kappaOverRho_.resize(n);
        const Scalar invDt = 1 / dt, invDt2 = invDt * invDt, relaxPerDt = relaxation_ * invDt, relaxPerDt2 = relaxation_ * invDt2;
        const Scalar* alphaOverRho = f.alphaOverRho->data();
        const auto& ff = lists.own();
        ownPressureWalls_ = step.core.boundariesHaveOwnPressure(s);
        linearisedAt_ = &fluid.particles.position();
        if (ownPressureWalls_) {
            ownWallPush_.start(n);
            totalPressure_.resize(n);
        }

        // 1. divergence solve: remove the compressing part of the velocity field. Per iteration
        //    one pass for Dρ/Dt and the next κ/ρ, the average error, one pass for the velocities.
        if (divergenceSolve_) {
            int divergenceIterations = 0;
            auto& kv = *f.kappaV;
            // warm start only where the fluid still compresses (SPlisHSPlasH's condition: a
            // surface particle's last push, carried into a step where it expands, shot the
            // Colagrossi column's top layer up at 11 m/s)
            const auto warmWhereCompressing = [&](std::size_t i, Scalar rate) {
                const bool full = ff.count(i) + lists.otherNeighbourCount(i) >= minNeighbours_;
                if (!(full && rate > 0)) kv[i] = 0;
            };
            if (warmStart_ > 0) densityRatePass(s, fluid, warmWhereCompressing, WarmStartRateTerm{{}, kv.data()});
            warmStartVelocities(s, fluid, kv, dt, invDt);
            pushOfOwnPressureWalls(s, fluid, step, kv, nullptr);
            for (;;) {
                densityRatePass(s, fluid, [&](std::size_t i, Scalar rate) {
                    const bool full = ff.count(i) + lists.otherNeighbourCount(i) >= minNeighbours_;
                    rate = full ? std::max(rate, Scalar(0)) : Scalar(0);
                    rate_[i] = rate;
                    kappaOverRho_[i] = rate * alphaOverRho[i] * relaxPerDt;
                });
                const double error = dt * deterministicSum(n, [&](std::size_t i) { return rate_[i]; }) / (double(n) * rho0_);
                if (divergenceIterations >= maxDivergenceIterations_ ||
                    (divergenceIterations >= 1 && error <= maxDivergenceError_))
                    break;
                applyStiffness(s, fluid, dt, &kv);
                pushOfOwnPressureWalls(s, fluid, step, kv, nullptr);
                ++divergenceIterations;
            }
        }

        // 2. non-pressure accelerations
        forEachIndex(n, [&](std::size_t i) { velocity_[i] += dt * a[i]; });

        // 3. density solve: the predicted density ρ*_i = ρ_i + δ_i + Δt Dρ_i/Dt back to ρ0. With
        //    checkPositions, a solve that meets η is checked on the density at the positions
        //    x + Δt v* it leads to (a neighbour search and density there); δ_i takes up the
        //    difference (the linearisation error, O(Δt²), kept for the next step). A check that
        //    passes leaves the search and density of the next step. One that fails
        //    linearises again about the checked positions: their lists, gradients and α, and
        //    ρ*_i = ρ_i(x + Δt v*) + Δt (Dρ_i/Dt(v) − Dρ_i/Dt(v*)) there; the solve goes on until
        //    a check passes.
        auto& k = *f.kappa;
        Scalar* offset = f.offset ? f.offset->data() : nullptr; // δ of the last step to start with
        baseDensity_.resize(n);
        forEachIndex(n, [&](std::size_t i) { baseDensity_[i] = rho[i] + (offset ? offset[i] : Scalar(0)); });
        warmStartVelocities(s, fluid, k, dt, invDt2);
        std::vector<Scalar>* kv = divergenceSolve_ ? f.kappaV : nullptr;
        pushOfOwnPressureWalls(s, fluid, step, k, kv);
        const auto stiffness = [&](std::size_t i, Scalar predicted) {
            rate_[i] = predicted;
            kappaOverRho_[i] = std::max(predicted - rho0_, Scalar(0)) * alphaOverRho[i] * relaxPerDt2;
        };
        int iterations = 0, checks = 0;
        CompressionError err;
        for (;;) {
            densityRatePass(s, fluid, [&](std::size_t i, Scalar rate) { stiffness(i, baseDensity_[i] + dt * rate); });
            err = compressionError(rate_, rho0_);
            if (controls_.done(iterations, err.max, err.avg)) {
                if (!checkPositions_ || iterations >= controls_.maxIterations || checks == maxPositionChecks) break;
                searchAhead(s, fluid, step);
                ++checks;
                const auto& next = *f.nextDensity;
                err = compressionError(next, rho0_);
                if (controls_.converged(err.max, err.avg)) {
                    forEachIndex(n, [&](std::size_t i) { offset[i] += next[i] - rate_[i]; });
                    checkPassed(fluid) = 1; // the next evaluation's search and density
                    break;
                }
                linearisedAt_ = &nextPositions_;
                densityRatePass(s, fluid, [&](std::size_t i, Scalar rate) { // Dρ/Dt(v*) about the checked positions
                    const Scalar real = next[i];
                    offset[i] += real - rate_[i];
                    stiffness(i, real);
                    baseDensity_[i] = real - dt * rate;
                });
            }
            applyStiffness(s, fluid, dt, &k);
            pushOfOwnPressureWalls(s, fluid, step, k, kv);
            ++iterations;
        }

        forEachIndex(n, [&](std::size_t i) {
            a[i] = (velocity_[i] - v[i]) * invDt;
            // κ is p/ρ (eq. 9); the step's pressure acts in both solves: the divergence solve's
            // κ_v (the velocities' compressing part) and the density solve's κ — p from κ alone
            // read a still column 34 % low
            p[i] = rho[i] * (k[i] + (kv ? (*kv)[i] : Scalar(0)));
            // kept for the next warm start as the step's velocity change per unit of κ's
            // gradient: κ_v Δt and κ Δt² (as SPlisHSPlasH), not κ, so a step of another Δt
            // starts from the same velocity change (a κ carried over from a step 2.5× shorter
            // applied 2.5× the push: the Colagrossi column's top shot up at 11 m/s while Δt grew)
            k[i] *= dt * dt;
            if (kv) (*kv)[i] *= dt;
        });
        stats_ = {iterations, controls_.converged(err.max, err.avg), err.max, err.avg};
    }

    // The wall term over both solves, with the step's total κ = p/ρ: on boundaries of their own
    // pressure a_ib = −M_b (p_i/ρ_i² + p_b/ρ_b²) ∇W_ib, p_b extrapolated from the step's final
    // pressure (the last correction's); on mirroring ones once, a_ib = −M_b (p_i/ρ_i²) ∇W_ib; at
    // the step's positions.
    void addReactions(const Scene& s, const ParticleSystem& fluid, const Step& step, Reactions& r) const override {
        const auto& p = fluid.particles.pressure();
        const auto& rho = fluid.particles.density();
        pOverRho2_.resize(p.size());
        forEachIndex(p.size(), [&](std::size_t i) { pOverRho2_[i] = p[i] / (rho[i] * rho[i]); });
        if (step.core.boundariesHaveOwnPressure(s))
            addSymmetricPressureReactions(s, fluid, fluid.particles.position(), pOverRho2_.data(), r);
        else
            addOneSidedWallPressureReactions(s, fluid, fluid.particles.position(), pOverRho2_.data(), r);
    }

    bool isIterative() const override { return true; }
    double maxTimeStep(const Scene& s, const StateSpeeds& v) const override { return controls_.maxTimeStep(s, v); }
    SolverStats lastSolve() const override { return stats_; }

private:
    static constexpr FieldOptions scratch{false, false, true};

    // Its fields of a fluid: κ of the density solve and κ of the divergence solve (restart
    // fields), δ (checkPositions), and the scratch of the density pass: α_i/ρ_i = 1/(eq. 8's
    // denominator), Σ_b M_b ∇W_ib, Σ_b M_b v_b·∇W_ib, the density at the positions of the last
    // check.
    struct Fields {
        std::vector<Scalar>*kappa, *kappaV, *offset, *nextDensity, *alphaOverRho, *wallRate;
        std::vector<Vec3>* wallGradient;
    };
    static Fields fieldsOf(ParticleSystem& fluid) {
        auto& set = fluid.particles;
        return {set.findScalar("dfsphKappa"),        set.findScalar("dfsphKappaV"),
                set.findScalar("dfsphDensityOffset"), set.findScalar("dfsphNextDensity"),
                set.findScalar("dfsphAlphaOverRho"), set.findScalar("dfsphWallRate"),
                set.findVector("dfsphWallGradient")};
    }
    // Whether the last solve's check of the fluid passed: its search is then the next step's.
    char& checkPassed(const ParticleSystem& fluid) {
        if (checkPassed_.size() <= fluid.index) checkPassed_.resize(fluid.index + 1, 0);
        return checkPassed_[fluid.index];
    }
    std::vector<char> checkPassed_;

    // FluidDivergenceTerm for the particles that carry a warm start (κ_v ≠ 0) only: for the
    // others Dρ/Dt decides nothing, as their warm start is zero.
    struct WarmStartRateTerm : FluidDivergenceTerm {
        const Scalar* kappaV;
        bool visits(std::size_t i) const { return kappaV[i] != 0; }
    };

    // then(i, Dρ_i/Dt) with Dρ_i/Dt = m Σ_j (u_i − u_j)·∇W_ij + u_i·Σ_b M_b ∇W_ib − Σ_b M_b v_b·∇W_ib
    // of velocity_ (the cached gradients; the walls' sums were taken with the density, so no wall
    // pair is visited in the solves); with a term that visits only some particles, for those.
    template <class Then, class Term = FluidDivergenceTerm>
    void densityRatePass(const Scene& s, ParticleSystem& fluid, Then&& then, Term term = {}) {
        const Scalar m = fluid.particles.particleMass();
        const Fields f = fieldsOf(fluid);
        const Vec3* g = f.wallGradient->data();
        const Scalar* wallRate = f.wallRate->data();
        term.u = velocity_.data();
        forEachCachedPairSum(s, fluid, term, [&](std::size_t i, const Vec3& ui, Scalar sum) {
            then(i, m * sum + ui.dot(g[i]) - wallRate[i]);
        });
    }

    // ρ_i, α_i, the pair gradients and the wall sums at positions x, on the lists of the search's
    // last build (which must be at x), the density into rho.
    void densityAndFactors(Scene& s, ParticleSystem& fluid, const std::vector<Vec3>& x, std::vector<Scalar>& rho) {
        const Scalar m = fluid.particles.particleMass(), w0 = s.kernel.W0(), h = s.constants.supportRadius;
        const Scalar tiny = Scalar(1e-9) * rho0_ * rho0_ / (h * h);
        rho.resize(x.size());
        const Fields f = fieldsOf(fluid);
        auto& alphaOverRho = *f.alphaOverRho;
        auto& wallGradient = *f.wallGradient;
        auto& wallRate = *f.wallRate;
        const auto factors = [&](std::size_t i, const DensityAndGradientSumsTerm::Sum& sum) {
            rho[i] = m * (w0 + sum.w) + sum.wall;
            wallGradient[i] = sum.wallGrad;
            wallRate[i] = sum.wallRate;
            const Vec3 g = m * sum.grad + sum.wallGrad;
            const Scalar denominator = g.squaredNorm() + m * m * sum.squares;
            alphaOverRho[i] = denominator > tiny ? 1 / denominator : Scalar(0);
        };
        densityAndGradientSums(s, fluid, x, factors);
    }

    // The check of checkPositions: the neighbour search, density, α and gradients at the
    // positions velocity_ leads to, computed as the integrator will (symplectic Euler with the
    // acceleration this model returns, then the core's drift), so that, when the check passes,
    // the next evaluation takes them bit for bit instead of searching again. The density goes to
    // the scratch field dfsphNextDensity; the step's own lists and factors are overwritten.
    void searchAhead(Scene& s, ParticleSystem& fluid, const Step& step) {
        const Scalar dt = step.dt, invDt = 1 / dt;
        const auto& v = fluid.particles.velocity();
        nextVelocity_.resize(v.size());
        forEachIndex(v.size(), [&](std::size_t i) {
            const Vec3 a = (velocity_[i] - v[i]) * invDt;
            nextVelocity_[i] = v[i] + dt * a; // as symplectic Euler computes v_{n+1}
        });
        step.core.drift(s, fluid, dt, nextVelocity_, nextPositions_);
        s.search.buildAhead(fluid.index, nextPositions_);
        densityAndFactors(s, fluid, nextPositions_, *fieldsOf(fluid).nextDensity);
    }

    // velocity_ −= Δt [Σ_j m (κ_i/ρ_i + κ_j/ρ_j) ∇W_ij + κ_i/ρ_i Σ_b M_b ∇W_ib], κ/ρ in
    // kappaOverRho_; κ_i is added to *kappa (the step's total) when given.
    void applyStiffness(const Scene& s, ParticleSystem& fluid, Scalar dt, std::vector<Scalar>* kappa) {
        const Scalar m = fluid.particles.particleMass();
        const auto& rho = fluid.particles.density();
        const Vec3* g = fieldsOf(fluid).wallGradient->data();
        Scalar* total = kappa ? kappa->data() : nullptr;
        forEachCachedPairSum(s, fluid, CachedSymmetricGradientTerm{kappaOverRho_.data()}, [&](std::size_t i, Scalar ki, const Vec3& dv) {
            velocity_[i] -= dt * (m * dv + ki * g[i]);
            if (total) total[i] += ki * rho[i];
        });
    }

    // Boundaries of their own pressure (adami): the core carries the fluid's pressure of the step
    // so far, p_i = ρ_i (κ_i + κ^v_i) (the stiffness κ of the solve under way and, in the density
    // solve, the divergence solve's κ^v), to the boundaries, and velocity_ takes the change of
    // their push since the last call,
    //   Δv_i = −Δt Δ[Σ_b M_b p_b/ρ_b² ∇W_ib],
    // so that over the step the walls push with the pressure the fluid ends with: the symmetric
    // term M_b (κ_i/ρ_i + p_b/ρ_b²) ∇W_ib (with applyStiffness's κ_i/ρ_i part), as pcisph and iisph
    // apply it. p_b carries Adami's hydrostatic term, so the row beside a wall is held as the rows
    // inside the fluid are.
    void pushOfOwnPressureWalls(Scene& s, const ParticleSystem& fluid, const Step& step, const std::vector<Scalar>& kappa,
                                const std::vector<Scalar>* other) {
        if (!ownPressureWalls_) return;
        const auto& rho = fluid.particles.density();
        forEachIndex(kappa.size(), [&](std::size_t i) { totalPressure_[i] = rho[i] * (kappa[i] + (other ? (*other)[i] : Scalar(0))); });
        const Scalar dt = step.dt;
        ownWallPush_.update(s, fluid, step, totalPressure_, *linearisedAt_,
                            [&](std::size_t i, const Vec3& change) { velocity_[i] -= dt * change; });
    }

    // Applies warmStart × the last step's κ to velocity_ and keeps it as this step's start.
    // kappa holds the last step's κ Δt (divergence solve; perDt = 1/Δt) or κ Δt² (density solve;
    // perDt = 1/Δt²): the warm start is warmStart × that over this step's Δt.
    void warmStartVelocities(const Scene& s, ParticleSystem& fluid, std::vector<Scalar>& kappa, Scalar dt, Scalar perDt) {
        const std::size_t n = kappa.size();
        const auto& rho = fluid.particles.density();
        const Scalar w = warmStart_ * perDt;
        forEachIndex(n, [&](std::size_t i) {
            kappa[i] *= w;
            kappaOverRho_[i] = kappa[i] / rho[i];
        });
        if (w > 0) applyStiffness(s, fluid, dt, nullptr);
    }

    Scalar rho0_, warmStart_, omega_;
    Scalar relaxation_ = 1; // omega held to the bound (boundedJacobiRelaxation, LatticePrototype.hpp)
    bool divergenceSolve_, checkPositions_;
    static constexpr int maxPositionChecks = 10;
    Scalar maxDivergenceError_ = Scalar(0.001);
    int maxDivergenceIterations_ = 100;
    std::size_t minNeighbours_ = 20;
    IterativeSolverControls controls_;
    std::vector<Scalar> rate_, kappaOverRho_;
    std::vector<Vec3> velocity_, nextVelocity_, nextPositions_;
    mutable std::vector<Scalar> pOverRho2_; // scratch of addReactions
    // boundaries of their own pressure: their push, the positions the solve linearises about, and
    // the fluid pressure p_b is taken from
    bool ownPressureWalls_ = false;
    OwnWallPush ownWallPush_;
    const std::vector<Vec3>* linearisedAt_ = nullptr;
    std::vector<Scalar> totalPressure_;
    long checksTaken_ = 0, checksNotTaken_ = 0; // passed checks the next step took over, or not
    // the predicted density less Δt Dρ/Dt: ρ_i + δ_i, or about the positions of a failed check
    // ρ_i(x + Δt v*) − Δt Dρ_i/Dt(v*)
    std::vector<Scalar> baseDensity_;
    SolverStats stats_;
};
} // namespace

SPINDRIFT_PLUGIN(PressureModel, Dfsph)
