// artificial — Monaghan (1992) artificial viscosity (docs/MODELS.md §artificial):
// a_i = −Σ_j m_j Π_ij ∇_i W_ij,  Π_ij = −α c̄ μ_ij / ρ̄_ij for v_ij·r_ij < 0 (else 0),
// μ_ij = h v_ij·r_ij / (r² + 0.01 h²), with h the support radius, c̄ the sound speed.
// Walls act as particles of the fluid particle's density moving with the velocity the boundary
// model gives viscous terms (the wall's own, or Adami's no-slip extrapolation); wallFactor scales
// them (0 = free slip). Pairwise antisymmetric: momentum is conserved among fluid particles.
//
//   viscosity { type artificial; alpha 0.05; soundSpeed 20; wallFactor 1; }
#include "Plugin.hpp"
#include "PairLoop.hpp"
#include "ViscosityModel.hpp"

namespace {
using namespace spindrift;

// Π_ij without its constant factors: v_ij·r_ij / ((r² + ε) ρ̄_ij) ∇W_ij for approaching pairs.
struct ArtificialViscosityTerm : VelocityDensityTerm {
    struct Sum {
        Vec3 fluid = Vec3::Zero(), wall = Vec3::Zero();
    };
    static constexpr bool usesGradient = true;
    Scalar eps; // 0.01 h²
    void fluid(const Particle& pi, const Pair& q, Sum& sum) const {
        // approaching pairs only; min() instead of a branch (taken for half the pairs, unpredictably)
        const Scalar vr = std::min((pi.v - v[q.j]).dot(q.r), Scalar(0));
        sum.fluid += (vr / ((q.r2 + eps) * (pi.rho + rho[q.j]))) * q.gradW;
    }
    void wall(const Particle& pi, const WallPair& q, Sum& sum) const {
        const Scalar vr = std::min((pi.v - q.src.vViscous[q.j]).dot(q.r), Scalar(0));
        sum.wall += (q.mass() * vr / (q.r2 + eps)) * q.gradW;
    }
};

class Artificial final : public ViscosityModel {
public:
    explicit Artificial(const ModelContext& c)
        : alpha_(c.dict.getOrDefault<double>("alpha", 0.05)),
          soundSpeed_(c.dict.found("soundSpeed") ? c.dict.get<double>("soundSpeed") : 0.0),
          wallFactor_(c.dict.getOrDefault<double>("wallFactor", 1.0)), soundSpeedLocation_(c.dict.locationOf("soundSpeed")) {
        if (alpha_ < 0) throw InputError(c.dict.locationOf("alpha"), "alpha must not be negative", "alpha");
    }

    void initialise(Scene& s) override {
        if (soundSpeed_ <= 0) soundSpeed_ = s.constants.soundSpeed;
        if (soundSpeed_ <= 0)
            throw InputError(soundSpeedLocation_, "artificial viscosity needs a sound speed: the pressure "
                                                  "model has none (incompressible), so give 'soundSpeed'", "soundSpeed");
    }

    void addAcceleration(Scene& s, ParticleSystem& fluid, const Step&) override {
        const Scalar m = fluid.particles.particleMass(), h = s.constants.supportRadius, ach = alpha_ * soundSpeed_ * h;
        const auto& rho = fluid.particles.density();
        auto& a = fluid.particles.acceleration();
        // −m Π_ij ∇W_ij = 2 m α c h · v_ij·r_ij / ((r² + ε)(ρ_i + ρ_j)) ∇W_ij; walls with ρ_b = ρ_i
        const Scalar fluidScale = 2 * m * ach, wallScale = wallFactor_ * ach;
        forEachPairSum(s, fluid, fluid.particles.position(), termOf(s, fluid),
                       [&](std::size_t i, const auto&, const auto& sum) {
                           a[i] += fluidScale * sum.fluid + (wallScale / rho[i]) * sum.wall;
                       });
    }
    // a_ib = (wallFactor α c h / ρ_i) × the term's wall part
    void addReactions(const Scene& s, const ParticleSystem& fluid, const Step&, Reactions& r) const override {
        const Scalar wallScale = wallFactor_ * alpha_ * soundSpeed_ * s.constants.supportRadius;
        const ArtificialViscosityTerm term = termOf(s, fluid);
        spindrift::addReactions(s, fluid, fluid.particles.position(), term, [&](std::size_t, const auto& pi, const WallPair& q) {
            ArtificialViscosityTerm::Sum c;
            term.wall(pi, q, c);
            return Vec3((wallScale / pi.rho) * c.wall);
        }, ForceKind::viscous, r);
    }

private:
    ArtificialViscosityTerm termOf(const Scene& s, const ParticleSystem& fluid) const {
        const Scalar h = s.constants.supportRadius;
        return {{fluid.particles.velocity().data(), fluid.particles.density().data()}, Scalar(0.01) * h * h};
    }

    Scalar alpha_, soundSpeed_, wallFactor_;
    SourceLocation soundSpeedLocation_;
};
} // namespace

SPINDRIFT_PLUGIN(ViscosityModel, Artificial)
