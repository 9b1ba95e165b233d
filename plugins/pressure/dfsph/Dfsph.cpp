// dfsph — divergence-free SPH (Bender & Koschier 2015, "Divergence-Free Smoothed Particle
// Hydrodynamics", SCA; 2017 TVCG, Alg. 1–3), the incompressible solver SPlisHSPlasH defaults
// to. Two Jacobi solves on the step's neighbour lists, both on velocities (no prediction of
// positions, no second neighbour search unless checkPositions), with a per-particle factor
//   α_i = ρ_i / (|Σ_j m ∇W_ij + Σ_b M_b ∇W_ib|² + Σ_j |m ∇W_ij|²)                 (eq. 8)
// and the rate of density change Dρ_i/Dt = Σ_j m (v_i − v_j)·∇W_ij + Σ_b M_b v_i·∇W_ib (walls at rest).
// A stiffness κ_i (= p_i/ρ_i) changes the velocities by
//   v_i −= Δt [Σ_j m (κ_i/ρ_i + κ_j/ρ_j) ∇W_ij + Σ_b M_b κ_i/ρ_i ∇W_ib]
// (the wall term once, as SPlisHSPlasH: the fluid column stays calm, but the pressure p = ρκ of
// the particles touching a wall is about twice the physical one; mirroring κ_b = κ_i instead,
// as the other solvers mirror p, gave the right wall pressure but a restless column).
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
//      the next step, whose evaluation then skips the search (PressureModel::searchedAt; over
//      a re-sort of the particles the lists are relabelled and this model's data reordered,
//      permute), so a passed check costs no more than the step it saves. A failed one
//      linearises again about the checked positions (their lists and factors;
//      ρ*_i = ρ_i(x + Δt v*) + Δt ΔDρ_i/Dt of the velocity change since) and the solve goes on
//      until a check meets η. In the dam-break cube under CFL: 1.08 checks and 1.08 searches a
//      step.
// The positions the solves linearise about do not change (but at a failed check), so ∇W of every
// fluid pair is computed once, with the density (computeDensity, after the neighbour search), and
// the solver passes (and the viscosity, through SphSystem::fluidPairGradients) only stream it;
// the walls are at rest, so their terms need only Σ_b M_b ∇W_ib per particle, also computed once.
// Both solves warm-start from half of the last step's κ (fields dfsphKappa, dfsphKappaV:
// restarts continue bit for bit). The model returns (v* − v)/Δt as its acceleration, so symplectic
// Euler gives v_{n+1} = v*, x_{n+1} = x_n + Δt v*. Wall particles b have mass M_b = ρ0 V_b
// (WallVolumes.hpp: uniform m/ρ0 by default, or the boundary model's adaptive volume).
//
//   pressure { type dfsph; warmStart 0.5; divergenceSolve yes; checkPositions no; boundaryVolume uniform; }
//   sphSolution: pressure { maxDensityError 0.001; densityErrorNorm average; minIterations 2;
//                           maxIterations 100; maxDivergenceError 0.001; maxDivergenceIterations 100; }
#include "IterativeSolverControls.hpp"
#include "Log.hpp"
#include "Plugin.hpp"
#include "PressureModel.hpp"
#include "SphOperators.hpp"
#include "WallVolumes.hpp"

#include <stdexcept>

namespace {
using namespace spindrift;

class Dfsph final : public PressureModel {
public:
    explicit Dfsph(const ModelContext& c)
        : rho0_(c.physics.rho0), warmStart_(c.dict.getOrDefault<double>("warmStart", 0.5)),
          divergenceSolve_(c.dict.getOrDefault<bool>("divergenceSolve", true)),
          checkPositions_(c.dict.getOrDefault<bool>("checkPositions", false)),
          adaptiveWalls_(readAdaptiveBoundaryVolume(c.dict, false)) {
        if (warmStart_ < 0 || warmStart_ > 1)
            throw InputError(c.dict.locationOf("warmStart"), "warmStart must be in [0, 1]", "warmStart");
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

    void initialise(SphSystem& s) override {
        wallVolume_ = wallVolumes(s, adaptiveWalls_, "dfsph");
        kappa_ = &s.fluid.addScalar("dfsphKappa", {false, true});
        kappaV_ = &s.fluid.addScalar("dfsphKappaV", {false, true});
        if (checkPositions_) offset_ = &s.fluid.addScalar("dfsphDensityOffset", {false, true});
        minNeighbours_ = s.physics.dimension == 3 ? 20 : 7;
        s.soundSpeed = 0;
    }

    // ρ_i, α_i, the pair gradients and the wall gradient sum at the current positions; taken
    // over from the last step's check when it searched at exactly these positions.
    void computeDensity(SphSystem& s) override {
        if (searchedAt(s)) {
            s.fluid.density().swap(nextDensity_);
            searchedAhead_ = false;
            ++checksTaken_;
            s.fluidPairGradients = &gradFluid_;
            return;
        }
        if (searchedAhead_ && ++checksNotTaken_ == 20 && checksTaken_ == 0)
            log::warning("dfsph: the positions of the step are never those checkPositions checked (x + deltaT v, "
                         "as symplecticEuler computes them): the check is approximate and costs a neighbour "
                         "search of its own each step");
        searchedAhead_ = false;
        densityAndFactors(s, s.fluid.position(), s.fluid.density());
    }

    // The last step's check built the lists (and this model's density, α and gradients) at the
    // positions the step led to; when the integrator reached exactly those, evaluate() takes
    // them instead of searching again.
    bool searchedAt(const SphSystem& s) const override {
        return searchedAhead_ && s.fluid.position() == nextPositions_;
    }

    // A re-sort of the particles keeps the check's search (Simulation relabels the lists): its
    // positions, density, α, wall gradient sums and pair gradients in the new order, rows of
    // the old lists taken in that order (the relabelled lists keep each row's pair order).
    void permute(const SphSystem& s, const std::vector<Index>& order) override {
        const auto& ff = s.search.fluidNeighbours(); // still in the old order
        std::vector<Vec3> gradients;
        permuteRowData(ff, order, permutedOffsets(ff, order), gradFluid_, gradients);
        gradFluid_.swap(gradients);
        permuteVector(nextPositions_, order);
        permuteVector(nextDensity_, order);
        permuteVector(alphaOverRho_, order);
        permuteVector(wallGradient_, order);
    }

    void addPressureAcceleration(SphSystem& s, Scalar dt) override {
        const std::size_t n = s.fluid.size();
        const auto& v = s.fluid.velocity();
        const auto& rho = s.fluid.density();
        auto& a = s.fluid.acceleration();
        auto& p = s.fluid.pressure();
        if (gradFluid_.size() != s.search.fluidNeighbours().totalPairs() || wallGradient_.size() != n)
            throw std::logic_error("dfsph: computeDensity must run after each neighbour search (it caches the gradients)");
        velocity_.resize(n);
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < n; ++i) velocity_[i] = v[i];
        rate_.resize(n);
        kappaOverRho_.resize(n);
        const Scalar invDt = 1 / dt, invDt2 = invDt * invDt;
        const Scalar* alphaOverRho = alphaOverRho_.data();
        const auto& ff = s.search.fluidNeighbours();
        const auto& fb = s.search.boundaryNeighbours();

        // 1. divergence solve: remove the compressing part of the velocity field. Per iteration
        //    one pass for Dρ/Dt and the next κ/ρ, the average error, one pass for the velocities.
        if (divergenceSolve_) {
            int divergenceIterations = 0;
            auto& kv = *kappaV_;
            warmStartVelocities(s, kv, dt);
            for (;;) {
                densityRatePass(s, [&](std::size_t i, Scalar rate) {
                    rate = ff.count(i) + fb.count(i) >= minNeighbours_ ? std::max(rate, Scalar(0)) : Scalar(0);
                    rate_[i] = rate;
                    kappaOverRho_[i] = rate * alphaOverRho[i] * invDt;
                });
                const double error = dt * deterministicSum(n, [&](std::size_t i) { return rate_[i]; }) / (double(n) * rho0_);
                if (divergenceIterations >= maxDivergenceIterations_ ||
                    (divergenceIterations >= 1 && error <= maxDivergenceError_))
                    break;
                applyStiffness(s, dt, &kv);
                ++divergenceIterations;
            }
        }

        // 2. non-pressure accelerations
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < n; ++i) velocity_[i] += dt * a[i];

        // 3. density solve: the predicted density ρ*_i = ρ_i + δ_i + Δt Dρ_i/Dt back to ρ0. With
        //    checkPositions, a solve that meets η is checked on the density at the positions
        //    x + Δt v* it leads to (a neighbour search and density there); δ_i takes up the
        //    difference (the linearisation error, O(Δt²), kept for the next step). A check that
        //    passes leaves the search and density of the next step. One that fails
        //    linearises again about the checked positions: their lists, gradients and α, and
        //    ρ*_i = ρ_i(x + Δt v*) + Δt (Dρ_i/Dt(v) − Dρ_i/Dt(v*)) there; the solve goes on until
        //    a check passes.
        auto& k = *kappa_;
        warmStartVelocities(s, k, dt);
        Scalar* offset = offset_ ? offset_->data() : nullptr; // δ of the last step to start with
        baseDensity_.resize(n);
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < n; ++i) baseDensity_[i] = rho[i] + (offset ? offset[i] : Scalar(0));
        const auto stiffness = [&](std::size_t i, Scalar predicted) {
            rate_[i] = predicted;
            kappaOverRho_[i] = std::max(predicted - rho0_, Scalar(0)) * alphaOverRho_[i] * invDt2;
        };
        int iterations = 0, checks = 0;
        CompressionError err;
        for (;;) {
            densityRatePass(s, [&](std::size_t i, Scalar rate) { stiffness(i, baseDensity_[i] + dt * rate); });
            err = compressionError(rate_, rho0_);
            if (controls_.done(iterations, err.max, err.avg)) {
                if (!checkPositions_ || iterations >= controls_.maxIterations || checks == maxPositionChecks) break;
                searchAhead(s, dt);
                ++checks;
                err = compressionError(nextDensity_, rho0_);
                if (controls_.converged(err.max, err.avg)) {
#pragma omp parallel for schedule(static)
                    for (std::size_t i = 0; i < n; ++i) offset[i] += nextDensity_[i] - rate_[i];
                    searchedAhead_ = true; // the next evaluation's search and density
                    break;
                }
                densityRatePass(s, [&](std::size_t i, Scalar rate) { // Dρ/Dt(v*) about the checked positions
                    const Scalar real = nextDensity_[i];
                    offset[i] += real - rate_[i];
                    stiffness(i, real);
                    baseDensity_[i] = real - dt * rate;
                });
            }
            applyStiffness(s, dt, &k);
            ++iterations;
        }

#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < n; ++i) {
            a[i] = (velocity_[i] - v[i]) * invDt;
            p[i] = rho[i] * k[i]; // κ is p/ρ (eq. 9)
        }
        stats_ = {iterations, controls_.converged(err.max, err.avg), err.max, err.avg};
    }

    Scalar soundSpeed() const override { return 0; }
    bool isIterative() const override { return true; }
    SolverStats lastSolve() const override { return stats_; }

private:
    // then(i, Dρ_i/Dt) with Dρ_i/Dt of velocity_ (the cached gradients; the walls at rest give
    // Σ_b M_b v_i·∇W_ib = v_i·Σ_b M_b ∇W_ib, so no wall pair is visited in the solves).
    template <class Then> void densityRatePass(const SphSystem& s, Then&& then) {
        const Scalar m = s.fluid.particleMass();
        const auto& ff = s.search.fluidNeighbours();
        const Vec3* u = velocity_.data();
        forEachParticleBalanced(s.search, [&](std::size_t i) {
            const Vec3 ui = u[i];
            Scalar fluid = 0;
            for (std::uint32_t k = ff.offsets[i]; k < ff.offsets[i + 1]; ++k)
                fluid += (ui - u[ff.indices[k]]).dot(gradFluid_[k]);
            then(i, m * fluid + ui.dot(wallGradient_[i]));
        }, NeighbourSearch::PairWork::Fluid);
    }

    // ρ_i, α_i, the pair gradients and the wall gradient sum at positions x, on the lists of
    // the search's last build (which must be at x), the density into rho.
    void densityAndFactors(SphSystem& s, const std::vector<Vec3>& x, std::vector<Scalar>& rho) {
        const auto& kt = s.kernel;
        const Scalar m = s.fluid.particleMass();
        const WallMasses walls = wallMassesOf(s, wallVolume_);
        const auto& ff = s.search.fluidNeighbours();
        const auto& fb = s.search.boundaryNeighbours();
        const auto& xb = s.boundary.position();
        rho.resize(x.size());
        alphaOverRho_.resize(x.size());
        wallGradient_.resize(x.size());
        gradFluid_.resize(ff.totalPairs());
        forEachParticleBalanced(s.search, [&](std::size_t i) {
            Scalar sum = kt.W0(), squares = 0;
            Vec3 grad = Vec3::Zero();
            Vec3* gi = gradFluid_.data() + ff.offsets[i];
            forEachNeighbour(ff, x, x, i, [&](Index, const Vec3& rij, Scalar r2) {
                sum += kt.WSq(r2);
                const Vec3 g = kt.gradWSq(rij, r2);
                *gi++ = g;
                grad += g;
                squares += g.squaredNorm();
            });
            Scalar wall = 0;
            Vec3 gradWall = Vec3::Zero();
            if (walls.weight)
                forEachNeighbour(fb, x, xb, i, [&](Index b, const Vec3& rib, Scalar r2) {
                    wall += walls.weight[b] * kt.WSq(r2);
                    gradWall += walls.weight[b] * kt.gradWSq(rib, r2);
                });
            rho[i] = m * sum + walls.scale * wall;
            wallGradient_[i] = walls.scale * gradWall;
            const Vec3 g = m * grad + wallGradient_[i];
            const Scalar denominator = g.squaredNorm() + m * m * squares;
            alphaOverRho_[i] = denominator > Scalar(1e-9) * rho0_ * rho0_ / (kt.supportRadius() * kt.supportRadius())
                                   ? 1 / denominator
                                   : Scalar(0);
        });
        s.fluidPairGradients = &gradFluid_;
    }

    // The check of checkPositions: the neighbour search, density, α and gradients at the
    // positions velocity_ leads to, computed as the integrator will (symplectic Euler with the
    // acceleration this model returns, then the periodic wrap), so that, when the check
    // passes, the next evaluation takes them bit for bit instead of searching again. The
    // density goes to nextDensity_; the step's own lists and factors are overwritten.
    void searchAhead(SphSystem& s, Scalar dt) {
        const auto& x = s.fluid.position();
        const auto& v = s.fluid.velocity();
        const Periodicity& periodic = s.search.periodicity();
        const std::size_t n = x.size();
        const Scalar invDt = 1 / dt;
        nextPositions_.resize(n);
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < n; ++i) {
            const Vec3 a = (velocity_[i] - v[i]) * invDt;
            const Vec3 vNext = v[i] + dt * a;
            nextPositions_[i] = x[i] + dt * vNext;
            if (periodic.any()) periodic.wrap(nextPositions_[i]);
        }
        s.search.build(nextPositions_);
        densityAndFactors(s, nextPositions_, nextDensity_);
    }

    // velocity_ −= Δt [Σ_j m (κ_i/ρ_i + κ_j/ρ_j) ∇W_ij + κ_i/ρ_i Σ_b M_b ∇W_ib], κ/ρ in
    // kappaOverRho_; κ_i is added to *kappa (the step's total) when given.
    void applyStiffness(const SphSystem& s, Scalar dt, std::vector<Scalar>* kappa) {
        const Scalar m = s.fluid.particleMass();
        const auto& ff = s.search.fluidNeighbours();
        const auto& rho = s.fluid.density();
        const Scalar* kr = kappaOverRho_.data();
        Scalar* total = kappa ? kappa->data() : nullptr;
        forEachParticleBalanced(s.search, [&](std::size_t i) {
            const Scalar ki = kr[i];
            Vec3 dv = Vec3::Zero();
            for (std::uint32_t k = ff.offsets[i]; k < ff.offsets[i + 1]; ++k)
                dv += (ki + kr[ff.indices[k]]) * gradFluid_[k];
            velocity_[i] -= dt * (m * dv + ki * wallGradient_[i]);
            if (total) total[i] += ki * rho[i];
        }, NeighbourSearch::PairWork::Fluid);
    }

    // Applies warmStart × the last step's κ to velocity_ and keeps it as this step's start.
    void warmStartVelocities(const SphSystem& s, std::vector<Scalar>& kappa, Scalar dt) {
        const std::size_t n = kappa.size();
        const auto& rho = s.fluid.density();
        const Scalar w = warmStart_;
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < n; ++i) {
            kappa[i] *= w;
            kappaOverRho_[i] = kappa[i] / rho[i];
        }
        if (w > 0) applyStiffness(s, dt, nullptr);
    }

    Scalar rho0_, warmStart_;
    bool divergenceSolve_, checkPositions_, adaptiveWalls_;
    static constexpr int maxPositionChecks = 10;
    Scalar maxDivergenceError_ = Scalar(0.001);
    int maxDivergenceIterations_ = 100;
    std::size_t minNeighbours_ = 20;
    IterativeSolverControls controls_;
    std::vector<Scalar> wallVolume_, alphaOverRho_, rate_, kappaOverRho_; // α_i/ρ_i = 1/(eq. 8's denominator)
    std::vector<Scalar>* kappa_ = nullptr;  // field dfsphKappa: κ of the density solve
    std::vector<Scalar>* kappaV_ = nullptr; // field dfsphKappaV: κ of the divergence solve
    std::vector<Scalar>* offset_ = nullptr; // field dfsphDensityOffset (checkPositions): δ
    std::vector<Vec3> velocity_;
    // checkPositions: where the last passed check searched, the density there, and whether the
    // search's lists and the factors are still those
    std::vector<Vec3> nextPositions_;
    std::vector<Scalar> nextDensity_;
    bool searchedAhead_ = false;
    long checksTaken_ = 0, checksNotTaken_ = 0; // passed checks the next step took over, or not
    // the predicted density less Δt Dρ/Dt: ρ_i + δ_i, or about the positions of a failed check
    // ρ_i(x + Δt v*) − Δt Dρ_i/Dt(v*)
    std::vector<Scalar> baseDensity_;
    std::vector<Vec3> gradFluid_;    // ∇W of every fluid pair of the lists the solves linearise about
    std::vector<Vec3> wallGradient_; // Σ_b M_b ∇W_ib of every fluid particle
    SolverStats stats_;
};
} // namespace

SPINDRIFT_PLUGIN(PressureModel, Dfsph)
