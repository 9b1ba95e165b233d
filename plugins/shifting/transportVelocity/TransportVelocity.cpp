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
// evaluation counts the fluid particles whose kernel sum (walls included) is below 75 % of a
// full one and warns when there are any; use `deltaPlus` for free-surface flows.
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

#include <sstream>

namespace {
using namespace spindrift;

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

// Σ_j m W_ij + Σ_b M_b W_ib (self excluded), for the free-surface check.
struct KernelSumTerm {
    using Sum = Scalar;
    struct Particle {};
    const KernelTable& kt;
    Scalar m;
    Particle particle(std::size_t) const { return {}; }
    void fluid(const Particle&, const Pair& q, Sum& sum) const { sum += m * kt.WSq(q.r2); }
    void wall(const Particle&, const WallPair& q, Sum& sum) const { sum += q.mass() * kt.WSq(q.r2); }
};

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
        shift_ = &s.fluid.addVector("shiftingVelocity");
    }

    void computeShift(Scene& s, Scalar dt) override {
        if (!checked_) {
            warnOfFreeSurface(s);
            checked_ = true;
        }
        auto& shift = *shift_;
        const Scalar rho0 = s.constants.rho0, scale = -dt * backgroundPressure_ / (rho0 * rho0);
        forEachPairSum(s, s.fluid.position(), ConcentrationGradientTerm{s.fluid.particleMass()},
                       [&](std::size_t i, const auto&, const Vec3& gradient) { shift[i] = scale * gradient; });
        if (!extraStress_) return;
        auto& a = s.fluid.acceleration();
        const ExtraStressTerm term{s.fluid.velocity().data(), shift.data(), s.fluid.density().data(),
                                   s.fluid.particleMass()};
        forEachPairSum(s, s.fluid.position(), term, [&](std::size_t i, const auto&, const Vec3& sum) { a[i] += sum; });
    }

private:
    // Warns when fluid particles have a truncated kernel (a free surface) at the first evaluation.
    void warnOfFreeSurface(const Scene& s) const {
        const Scalar m = s.fluid.particleMass(), full = s.constants.rho0, self = m * s.kernel.W0();
        std::vector<char> truncated(s.fluid.size(), 0);
        forEachPairSum(s, s.fluid.position(), KernelSumTerm{s.kernel, m},
                       [&](std::size_t i, const auto&, Scalar sum) { truncated[i] = self + sum < Scalar(0.75) * full; });
        std::size_t count = 0;
        for (char t : truncated) count += t;
        if (count == 0) return;
        std::ostringstream msg;
        msg << "shifting transportVelocity: " << count << " of " << s.fluid.size() << " fluid particles have less "
            << "than 75 % of a full kernel (a free surface): the transport-velocity formulation is for internal "
            << "flows, its background pressure pushes surface particles out of the fluid; use 'type deltaPlus;' "
            << "for flows with a free surface";
        log::warning(msg.str());
    }

    Scalar backgroundPressure_; // p_b [Pa]; < 0 until resolved from the equation of state
    bool extraStress_;
    SourceLocation where_;
    bool checked_ = false;
    std::vector<Vec3>* shift_ = nullptr;
};
} // namespace

SPINDRIFT_PLUGIN(ShiftingModel, TransportVelocity)
