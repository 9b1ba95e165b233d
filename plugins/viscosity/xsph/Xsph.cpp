// xsph — XSPH velocity smoothing (Monaghan 1989; the viscosity of position-based fluids,
// Macklin & Müller 2013; docs/MODELS.md §xsph): each step pulls a particle's velocity towards
// its neighbourhood's,
//   Δv_i = c Σ_j (m_j / ρ̄_ij) (v_j − v_i) W_ij,   ρ̄_ij = (ρ_i + ρ_j)/2,
// a change of velocity (ResultKind::velocityChange), added as Δv_i/Δt: a symplectic-Euler step
// applies exactly Δv_i (with the velocities at the start of the step; PBF applies it after the
// position update). The pair term is symmetric in i, j with an antisymmetric velocity
// difference: momentum is conserved to round-off and kinetic energy decreases. Walls
// (wallFactor > 0): their particles with mass M_b and the fluid particle's density, moving with
// the velocity viscous terms see; the default 0 smooths among fluid particles only, as PBF does.
//
//   viscosity { type xsph; c 0.01; wallFactor 0; }
#include "PairLoop.hpp"
#include "Plugin.hpp"
#include "ViscosityModel.hpp"

namespace {
using namespace spindrift;

struct XsphTerm : VelocityDensityTerm {
    using Sum = Vec3; // Σ (m_j/ρ̄_ij) (v_j − v_i) W_ij
    static constexpr bool usesKernel = true;
    Scalar m, wallFactor;
    bool visitsWalls;
    void fluid(const Particle& pi, const Pair& q, Sum& sum) const {
        sum += (2 * m * q.W / (pi.rho + rho[q.j])) * (v[q.j] - pi.v);
    }
    void wall(const Particle& pi, const WallPair& q, Sum& sum) const {
        sum += (wallFactor * q.mass() * q.W / pi.rho) * (q.src.vViscous[q.j] - pi.v);
    }
};

class Xsph final : public ViscosityModel {
public:
    explicit Xsph(const ModelContext& c)
        : c_(c.dict.getOrDefault<double>("c", 0.01)), wallFactor_(c.dict.getOrDefault<double>("wallFactor", 0.0)) {
        if (!(c_ >= 0 && c_ <= 1)) throw InputError(c.dict.locationOf("c"), "c must be in [0, 1]", "c");
        if (wallFactor_ < 0)
            throw InputError(c.dict.locationOf("wallFactor"), "wallFactor must not be negative", "wallFactor");
    }

    ResultKind result() const override { return ResultKind::velocityChange; }

    void addAcceleration(Scene& s, ParticleSystem& fluid, const Step& step) override {
        const Scalar dt = step.dt;
        if (!(dt > 0) || c_ == 0) return;
        const Scalar scale = c_ / dt;
        auto& a = fluid.particles.acceleration();
        forEachPairSum(s, fluid, fluid.particles.position(), termOf(fluid),
                       [&](std::size_t i, const auto&, const Vec3& sum) { a[i] += scale * sum; });
    }
    // (its velocity change over the step, as an acceleration)
    void addReactions(const Scene& s, const ParticleSystem& fluid, const Step& step, Reactions& r) const override {
        if (!(step.dt > 0) || c_ == 0) return;
        addScaledReactions(s, fluid, termOf(fluid), c_ / step.dt, ForceKind::viscous, r);
    }

private:
    XsphTerm termOf(const ParticleSystem& fluid) const {
        return {{fluid.particles.velocity().data(), fluid.particles.density().data()}, fluid.particles.particleMass(),
                wallFactor_, wallFactor_ != 0};
    }

    Scalar c_, wallFactor_;
};
} // namespace

SPINDRIFT_PLUGIN(ViscosityModel, Xsph)
