// pcisph — predictive–corrective incompressible SPH (Solenthaler & Pajarola 2009, seed 003,
// Algorithm 2 and eqs. 1–9; docs/MODELS.md §pcisph).
//
// Inside one call, on the step's neighbour lists, with the step's Δt:
//   p = w p_last (warmStart w, 0 by default: the paper's p = 0), a_p from it; repeat:
//     v* = v + Δt (a_nonp + a_p),  x* = x + Δt v*                       (prediction)
//     ρ*_i = m Σ_j W(x*_i − x*_j) + Σ_b M_b W(x*_i − x_b)               (eq. 1, walls included)
//     stop if iterations ≥ minIterations and the density error ≤ η, or at maxIterations, or
//       (unconverged) once the error has risen over 3 corrections in a row (risingLimit)
//     p_i += δ (ρ*_i − ρ0)                                                (eqs. 8–9)
//     a_p,i = −Σ_j m (p_i/ρ̂_i² + p_j/ρ̂_j²) ∇_i W_ij − Σ_b ρ0 V_b 2 p_i/ρ̂_i² ∇_i W_ib   (eq. 3)
// with ρ̂ = max(ρ, ρ0). δ's derivation takes ρ_i = ρ_j = ρ0 (§3); below ρ0 (free surfaces,
// splash fronts: a particle alone has about 0.3 ρ0) the particle's own density gave it up to
// ten times the response δ predicts, its correction overshot and the loop oscillated: in the
// speed benchmark's dam break at Δt = 2 ms a front particle was thrown back from the side wall
// at 38 m/s after 52 iterations and the run blew up at t = 0.35 s; with ρ̂ it runs the 1 s in
// 3.6 iterations a step. Compressed particles keep their own density: with ρ0 for every
// particle (as SPlisHSPlasH's PCISPH) a 3 %-compressed 3D block of Wendland C2 particles at
// 2.6Δx no longer converged with the paper's δ (its lattice gain, below, is 2.10; ρ_i ≈ 1.03 ρ0
// had kept the effective gain under 2).
// δ = −1/(β(−Σ∇W·Σ∇W − Σ∇W·∇W)), β = 2Δt²m²/ρ0², from a prototype particle with a full
// neighbourhood on the case's lattice (recomputed whenever Δt changes). δ is one particle's own
// response; a pressure wave over the lattice moves its neighbours too, and with many neighbours
// some waves respond more than twice as much, so the correction diverges on them
// (latticeMaxCorrectionGain: 2.84 for the Wendland C2 at 4Δx in 2D, where taylorGreen2D blew up in
// 7 steps; 2.10 at 2.6Δx in 3D, sinc² at 2.6Δx in 2D 2.03). Where the largest gain exceeds 1.8,
// δ is scaled by 1.8/gain; the usual supports (cubic spline at 2Δx: 1.41 in 3D; Wendland C2 at
// 2.6Δx in 2D: 1.30, at 3Δx: 1.67) keep the paper's δ, and their results are unchanged.
// The density error is the compression max(0, ρ* − ρ0)/ρ0; η, its norm (maximum by default:
// every particle, as in the paper) and the iteration limits come from system/sphSolution
// `pressure { }`. The check
// comes before each correction, so the returned acceleration is the one whose prediction met
// η: with symplectic Euler the next step starts from the verified prediction (leapfrog: the
// same for a constant Δt), up to neighbours that enter the support during the step (the
// paper's §2.4.1 approximation). Negative pressures are clamped to zero (free surfaces) unless
// clampNegativePressure no. Wall particles b take part with the masses M_b and the pressure
// (mirrored or their own) the boundary model gives them, at their positions of the step; walls
// of their own pressure (adami) have it extrapolated again from the fluid's at every correction.
//
// No warm start by default (issue 35): the pressure carried over from the last step is a delayed
// force that pumps the column's compression mode, which the three iterations do not damp. In the
// hydrostatic tank (validation case, adami walls, 1 ms steps) the bottom probe rang with a period
// of ~29 steps at ±65 % of ρ0 g (H − z) with w = 0.5 (std 45 % over 1.5–2 s), and is still with
// w = 0 or 0.25 (std 0.0 %, mean +0.74 %); w = 1 leaves the column restless (0.2 m/s). The
// Colagrossi dam break (H/40): wall pressure noise 0.064 → 0.043, closest pair 0.53 → 0.55 Δx.
//
// With `gradientCorrection yes` a_p takes the kernel-corrected gradient (KernelCorrection.hpp,
// L_i at the step's positions): a standing wave loses 3.9 % of its height a period instead of
// 18 % (docs/MODELS.md §pcisph).
//
//   pressure { type pcisph; clampNegativePressure yes; warmStart 0; gradientCorrection no; }
//   sphSolution: pressure { maxDensityError 0.01; densityErrorNorm maximum;
//                           minIterations 3; maxIterations 100; }
#include "DensityAndGradientSums.hpp"
#include "IterativeSolverControls.hpp"
#include "KernelCorrection.hpp"
#include "LatticePrototype.hpp"
#include "Log.hpp"
#include "Plugin.hpp"
#include "PairLoop.hpp"
#include "PressureModel.hpp"

#include <algorithm>
#include <limits>
#include <sstream>

namespace {
using namespace spindrift;

class Pcisph final : public PressureModel {
public:
    explicit Pcisph(const ModelContext& c)
        : rho0_(c.physics.rho0), clampNegative_(c.dict.getOrDefault<bool>("clampNegativePressure", true)),
          warmStart_(c.dict.getOrDefault<double>("warmStart", 0.0)),
          corrected_(c.dict.getOrDefault<bool>("gradientCorrection", false)) {
        if (!(warmStart_ >= 0 && warmStart_ <= 1))
            throw InputError(c.dict.locationOf("warmStart"), "warmStart must be in [0, 1]", "warmStart");
        controls_.read(c.solution); // defaults: η 1 % of the maximum, 3 to 100 iterations
    }

    void initialise(Scene& s) override {
        prototype_ = latticeGradientSums(s.kernel, s.physics.particleSpacing, s.physics.dimension);
        if (!(prototype_.sumGradSquared > 0))
            throw std::runtime_error("pcisph: the prototype particle has no neighbours (supportRadius too small)");
        const double gain = latticeMaxCorrectionGain(s.kernel, s.physics.particleSpacing, s.physics.dimension);
        deltaScale_ = jacobiRelaxationScale(gain);
        std::ostringstream m;
        m << "pcisph: prototype particle with " << prototype_.neighbours << " lattice neighbours, "
          << "sum grad W . grad W = " << prototype_.sumGradSquared << ", |sum grad W|^2 = " << prototype_.gradSumSquared
          << "; largest correction gain of a lattice wave " << gain;
        if (deltaScale_ < 1) m << " (the correction diverges above 2): delta scaled by " << deltaScale_;
        log::info(m.str());
    }

    // ρ_i, and in the same pass every fluid pair's ∇W_ij, kept in the scene's cache: the
    // pressure passes of the iterations (and the viscosity) at these positions stream it
    // instead of looking it up in the kernel table.
    void computeDensity(Scene& s, ParticleSystem& fluid, const Step&) override {
        const auto& x = fluid.particles.position();
        auto& rho = fluid.particles.density();
        const Scalar m = fluid.particles.particleMass(), w0 = s.kernel.W0();
        rho.resize(x.size());
        densityAndGradientSums(s, fluid, x, [&](std::size_t i, const DensityAndGradientSumsTerm::Sum& sum) {
            rho[i] = m * (w0 + sum.w) + sum.wall;
        });
    }

    void addPressureAcceleration(Scene& s, ParticleSystem& fluid, const Step& step) override {
        const Scalar dt = step.dt;
        const std::size_t n = fluid.size();
        const auto& x = fluid.particles.position();
        const auto& v = fluid.particles.velocity();
        const auto& rho = fluid.particles.density();
        auto& a = fluid.particles.acceleration();
        auto& p = fluid.particles.pressure();
        if (dt != deltaDt_) {
            delta_ = Scalar(deltaScale_ * pcisphDelta(prototype_, dt, fluid.particles.particleMass(), rho0_));
            deltaDt_ = dt;
        }
        nonPressure_.resize(n);
        pressureAcc_.resize(n);
        predicted_.resize(n);
        rhoPredicted_.resize(n);
        pOverRho2_.resize(n);
        // four parallel passes an iteration: density, error, pressure, acceleration + prediction
        const Scalar rho0 = rho0_, delta = delta_, w = warmStart_;
        const bool clamp = clampNegative_;
        // walls with a pressure of their own (adami) follow the fluid's at every correction
        const bool wallsOfTheirOwnPressure = step.core.boundariesHaveOwnPressure(s);
        Scalar* q = pOverRho2_.data();
        if (corrected_) kernelCorrectionMatrices(s, fluid, x, correction_);
        // a_p of q at the step's positions, and the prediction it makes
        const auto pressureAcceleration = [&] {
            const auto take = [&](std::size_t i, const Vec3& ap) {
                pressureAcc_[i] = ap;
                predicted_[i] = x[i] + dt * (v[i] + dt * (nonPressure_[i] + ap));
            };
            if (corrected_) correctedSymmetricPressureAcceleration(s, fluid, x, q, correction_.data(), take);
            else symmetricPressureAcceleration(s, fluid, x, q, take);
        };
        // the iteration starts from warmStart × the last step's pressure (the field holds it; at
        // the start, the initial pressure: a hydrostatic start's)
        forEachIndex(n, [&](std::size_t i) {
            nonPressure_[i] = a[i];
            pressureAcc_[i] = Vec3::Zero();
            p[i] *= w;
            const Scalar r = std::max(rho[i], rho0);
            q[i] = p[i] / (r * r);
            predicted_[i] = x[i] + dt * (v[i] + dt * a[i]);
        });
        if (w > 0) {
            if (wallsOfTheirOwnPressure) step.core.updateBoundaryPressure(s, fluid, p);
            pressureAcceleration();
        }
        int iterations = 0, rising = 0;
        Scalar lastError = std::numeric_limits<Scalar>::infinity();
        CompressionError err;
        for (;;) {
            summationDensity(s, fluid, predicted_, rhoPredicted_);
            err = compressionError(rhoPredicted_, rho0);
            if (controls_.done(iterations, err.max, err.avg)) break;
            // an error that rose over the last risingLimit corrections: the iteration diverges
            // (below), so it stops with the latest pressure, unconverged
            const Scalar e = controls_.error(err.max, err.avg);
            rising = e > lastError ? rising + 1 : 0;
            lastError = e;
            if (rising == risingLimit && iterations >= controls_.minIterations) break;
            forEachIndex(n, [&](std::size_t i) {
                const Scalar pi = p[i] + delta * (rhoPredicted_[i] - rho0);
                p[i] = clamp ? std::max(pi, Scalar(0)) : pi;
                const Scalar r = std::max(rho[i], rho0);
                q[i] = p[i] / (r * r);
            });
            if (wallsOfTheirOwnPressure) step.core.updateBoundaryPressure(s, fluid, p);
            pressureAcceleration();
            ++iterations;
        }
        forEachIndex(n, [&](std::size_t i) { a[i] = nonPressure_[i] + pressureAcc_[i]; });
        stats_ = {iterations, controls_.converged(err.max, err.avg), err.max, err.avg};
    }

    // the final pressure's (at the step's positions)
    void addReactions(const Scene& s, const ParticleSystem& fluid, const Step&, Reactions& r) const override {
        if (corrected_) addCorrectedSymmetricPressureReactions(s, fluid, pOverRho2_, correction_, r);
        else addSymmetricPressureReactions(s, fluid, fluid.particles.position(), pOverRho2_.data(), r);
    }

    bool isIterative() const override { return true; }
    double maxTimeStep(const Scene& s, const StateSpeeds& v) const override { return controls_.maxTimeStep(s, v); }
    SolverStats lastSolve() const override { return stats_; }

private:
    // Corrections in a row that raised the density error before the iteration stops. A particle
    // squeezed into a corner of the walls by the fluid behind it (the benchmark's dam break at
    // the impact, Δt = 2 ms) cannot be decompressed by its own pressure: pushed out, it runs
    // into the particles behind it, its predicted density rises again with its pressure, and
    // the correction kept raising both, for 47 iterations, to 0.8 MPa, throwing it at 24 m/s.
    static constexpr int risingLimit = 3;
    Scalar rho0_;
    bool clampNegative_;
    Scalar warmStart_; // the fraction of the last step's pressure the iteration starts from
    bool corrected_;   // gradientCorrection: the kernel-corrected gradient (KernelCorrection.hpp)
    std::vector<Mat3> correction_; // L_i at the step's positions
    IterativeSolverControls controls_;
    LatticeGradientSums prototype_;
    // δ is scaled down where a lattice wave's correction would exceed the gain 1.8
    // (jacobiRelaxationScale): each correction then shrinks every wave's error at least by 0.8
    double deltaScale_ = 1;
    Scalar delta_ = 0, deltaDt_ = -1;
    std::vector<Vec3> nonPressure_, pressureAcc_, predicted_;
    std::vector<Scalar> rhoPredicted_, pOverRho2_;
    SolverStats stats_;
};
} // namespace

SPINDRIFT_PLUGIN(PressureModel, Pcisph)
