// transportVelocity — the transport-velocity formulation of Adami, Hu & Adams (2013), J. Comput.
// Phys. 241, 292–307, doi:10.1016/j.jcp.2013.01.043; docs/MODELS.md §transportVelocity.
//
// Particles move with the transport velocity ṽ = v + δv instead of v. A constant background
// pressure p_b acts on the positions only (never on v), so it pushes particles from where they
// are crowded to where they are sparse and keeps the distribution regular — no clumping, no
// streaks along streamlines, no tensile instability — while the momentum equation, written along
// ṽ, gains the divergence of the extra stress A = ρ v ⊗ (ṽ − v):
//   δv_i = −(Δt/2) p_b Σ_j m (1/ρ0² + 1/ρ0²) ∇_i W_ij − (Δt/2) p_b Σ_b M_b (1/ρ0² + 1/ρ0²) ∇_i W_ib
//        = −Δt (p_b/ρ0²) [m Σ_j ∇_i W_ij + Σ_b M_b ∇_i W_ib]                          (paper eq. 12, 18)
//   a_i += Σ_j m (A_i/ρ_i² + A_j/ρ_j²)·∇_i W_ij + Σ_b M_b (A_i/ρ_i²)·∇_i W_ib,
//   (A/ρ²)·∇W = v (δv·∇W)/ρ                                                         (paper eq. 9)
// the same symmetric form as the pressure term (Spindrift's wcsph), with the sign of +∇·A/ρ.
// Wall particles (M_b, the boundary model's) count in both sums, A_b = 0 (walls have no δv),
// so fluid next to a wall is not pushed into it. Δt/2: the transport velocity of the paper's
// kick–drift–kick scheme, ṽ^{n+½} = v^{n+½} + (Δt/2) d̃v/dt.
// Deviation: the volumes of the background term are m/ρ0 (the reference density, as the first
// TrixiParticles implementation), not 1/Σ_j W_ij: with summation density the two differ by the
// density variation (O(Ma²)); with continuity density only this form is a gradient of the
// particle concentration alone, so it regularises without reacting to the pressure field.
//
// For internal flows only (the paper's scope): at a free surface the kernel is truncated, the
// background term points out of the fluid and the surface particles are sprayed away. The first
// evaluation looks for surface particles as deltaPlus does (Marrone et al. 2010: the smallest
// eigenvalue of B_i = −Σ_j V_j r_ij ⊗ ∇_i W_ij, walls included, below 0.75; a kernel-sum test
// misses a flat surface at a support of 2.6Δx, whose top row keeps 79 % of a full sum, and
// flags a disordered bulk) and warns when there are any; use `deltaPlus` for free-surface flows.
//
//   shifting
//   {
//       type                transportVelocity;
//       backgroundPressure  100;     // p_b [Pa]; default ρ0 c0² with the pressure model's c0
//       extraStress         yes;     // the A term in the momentum equation
//   }
#include "Log.hpp"
#include "PairLoop.hpp"
#include "Plugin.hpp"
#include "ShiftingModel.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <sstream>

namespace {
using namespace spindrift;

using Mat3 = Eigen::Matrix<Scalar, 3, 3>;

// m Σ_j ∇_i W_ij + Σ_b M_b ∇_i W_ib: the gradient of the particle concentration (times ρ0).
struct ConcentrationGradientTerm {
    using Sum = Vec3;
    static constexpr bool usesGradient = true;
    struct Particle {};
    Scalar m;
    Particle particle(std::size_t) const { return {}; }
    void fluid(const Particle&, const Pair& q, Sum& sum) const { sum += m * q.gradW; }
    void wall(const Particle&, const WallPair& q, Sum& sum) const { sum += q.mass() * q.gradW; }
};

// Σ_j m (v_i (δv_i·∇W)/ρ_i + v_j (δv_j·∇W)/ρ_j) + Σ_b M_b v_i (δv_i·∇W)/ρ_i: ∇·A/ρ.
struct ExtraStressTerm {
    using Sum = Vec3;
    static constexpr bool usesGradient = true;
    struct Particle {
        Vec3 v, shift; // v_i, δv_i/ρ_i
    };
    const Vec3* v;
    const Vec3* shift;
    const Scalar* rho;
    Scalar m;
    Particle particle(std::size_t i) const { return {v[i], shift[i] / rho[i]}; }
    void fluid(const Particle& pi, const Pair& q, Sum& sum) const {
        sum += m * (pi.shift.dot(q.gradW) * pi.v + (shift[q.j].dot(q.gradW) / rho[q.j]) * v[q.j]);
    }
    void wall(const Particle& pi, const WallPair& q, Sum& sum) const {
        sum += (q.mass() * pi.shift.dot(q.gradW)) * pi.v;
    }
};

// B = −Σ_j V_j r_ij ⊗ ∇_i W_ij over fluid and wall neighbours, V = m/ρ0 (M_b/ρ0 for walls): the
// renormalisation matrix of Marrone et al. (2010), for the free-surface check.
struct MomentTerm {
    using Sum = Mat3;
    static constexpr bool usesGradient = true;
    struct Particle {};
    Scalar V; // m/ρ0
    Scalar invRho0;
    Particle particle(std::size_t) const { return {}; }
    void fluid(const Particle&, const Pair& q, Sum& sum) const { sum.noalias() -= V * q.r * q.gradW.transpose(); }
    void wall(const Particle&, const WallPair& q, Sum& sum) const {
        sum.noalias() -= (q.mass() * invRho0) * q.r * q.gradW.transpose();
    }
};

// the smallest eigenvalue of the symmetric part of B in the problem's dimensions
Scalar smallestEigenvalue(const Mat3& B, int d) {
    if (d == 2) {
        const Scalar a = B(0, 0), c = B(1, 1), b = Scalar(0.5) * (B(0, 1) + B(1, 0));
        return Scalar(0.5) * (a + c) - std::sqrt(Scalar(0.25) * (a - c) * (a - c) + b * b);
    }
    if (d == 1) return B(0, 0);
    const Mat3 S = Scalar(0.5) * (B + B.transpose());
    Eigen::SelfAdjointEigenSolver<Mat3> solver;
    solver.computeDirect(S, Eigen::EigenvaluesOnly);
    return solver.eigenvalues()[0];
}

class TransportVelocity final : public ShiftingModel {
public:
    explicit TransportVelocity(const ModelContext& c)
        : backgroundPressure_(c.dict.found("backgroundPressure") ? c.dict.get<double>("backgroundPressure") : -1.0),
          extraStress_(c.dict.getOrDefault<bool>("extraStress", true)), where_(c.dict.where()) {
        if (c.dict.found("backgroundPressure") && !(backgroundPressure_ > 0))
            throw InputError(c.dict.locationOf("backgroundPressure"), "backgroundPressure must be positive",
                             "backgroundPressure");
    }

    void initialise(Scene& s) override {
        if (backgroundPressure_ < 0) {
            const Scalar c0 = s.constants.soundSpeed;
            if (!(c0 > 0))
                throw InputError(where_, "shifting transportVelocity: the pressure model has no sound speed (an "
                                     "incompressible solver): give 'backgroundPressure' explicitly",
                                 "backgroundPressure");
            backgroundPressure_ = s.constants.rho0 * c0 * c0;
            std::ostringstream m;
            m << "    default: backgroundPressure " << backgroundPressure_ << " Pa (rho0 c0^2)";
            log::info(m.str());
        }
    }

    void computeShift(Scene& s, ParticleSystem& fluid, const Step& step) override {
        if (!checked_) {
            warnOfFreeSurface(s, fluid);
            checked_ = true;
        }
        auto& shift = *fluid.particles.findVector("shiftingVelocity"); // (the core's field)
        const Scalar rho0 = fluid.rho0, scale = -step.dt * backgroundPressure_ / (rho0 * rho0);
        const auto& x = fluid.particles.position();
        forEachPairSum(s, fluid, x, ConcentrationGradientTerm{fluid.particles.particleMass()},
                       [&](std::size_t i, const auto&, const Vec3& gradient) { shift[i] = scale * gradient; });
        if (!extraStress_) return;
        auto& a = fluid.particles.acceleration();
        forEachPairSum(s, fluid, x, extraStressOf(fluid), [&](std::size_t i, const auto&, const Vec3& sum) { a[i] += sum; });
    }
    // the extra stress's boundary part (none without it)
    void addReactions(const Scene& s, const ParticleSystem& fluid, const Step&, Reactions& r) const override {
        if (extraStress_) addScaledReactions(s, fluid, extraStressOf(fluid), Scalar(1), ForceKind::other, r);
    }

private:
    static ExtraStressTerm extraStressOf(const ParticleSystem& fluid) {
        return {fluid.particles.velocity().data(), fluid.particles.findVector("shiftingVelocity")->data(),
                fluid.particles.density().data(), fluid.particles.particleMass()};
    }

    // Warns when fluid particles are on a free surface at the first evaluation: the smallest
    // eigenvalue λ of Marrone's B below 0.75 (≈ 1 inside the fluid, disordered or not, and next
    // to walls; ≈ 0.5 on a flat surface), as deltaPlus detects it.
    void warnOfFreeSurface(const Scene& s, const ParticleSystem& fluid) const {
        const Scalar rho0 = fluid.rho0;
        const int d = s.physics.dimension;
        std::vector<char> surface(fluid.size(), 0);
        forEachPairSum(s, fluid, fluid.particles.position(), MomentTerm{fluid.particles.particleMass() / rho0, 1 / rho0},
                       [&](std::size_t i, const auto&, const Mat3& B) {
                           surface[i] = smallestEigenvalue(B, d) < Scalar(0.75);
                       });
        std::size_t count = 0;
        for (char t : surface) count += t;
        if (count == 0) return;
        std::ostringstream msg;
        msg << "shifting transportVelocity: " << count << " of " << fluid.size() << " fluid particles are on "
            << "a free surface (the smallest eigenvalue of their renormalisation matrix is below 0.75): the "
            << "transport-velocity formulation is for internal flows, its background pressure pushes surface "
            << "particles out of the fluid; use 'type deltaPlus;' for flows with a free surface";
        log::warning(msg.str());
    }

    Scalar backgroundPressure_; // p_b [Pa]; < 0 until resolved from the equation of state
    bool extraStress_;
    SourceLocation where_;
    bool checked_ = false;
};
} // namespace

SPINDRIFT_PLUGIN(ShiftingModel, TransportVelocity)
