// Template viscosity plugin: XSPH velocity smoothing, a pair term on the core's pair loop
// (libsrc/PairLoop.hpp), which visits every fluid neighbour j and every wall or body particle b of
// each fluid particle i in the balanced parallel schedule:
//   Δv_i = c [Σ_j (2 m / (ρ_i + ρ_j)) (v_j − v_i) W_ij + Σ_b (M_b / ρ_i) (v_b − v_i) W_ib],
// a change of velocity, added as the acceleration Δv_i/Δt (ResultKind::velocityChange: the core
// accepts it with the symplecticEuler integrator).
//   sphSchemes:  viscosity { type <this folder's name>; c 0.01; }
#include "PairLoop.hpp"
#include "Plugin.hpp"
#include "ViscosityModel.hpp"

namespace {
using namespace spindrift;

struct SmoothingTerm {
    using Sum = Vec3;
    static constexpr bool usesKernel = true; // the loop hands each pair W_ij (q.W)
    struct Particle { Vec3 v; Scalar rho; };
    const Vec3* v;
    const Scalar* rho;
    Scalar m;
    Particle particle(std::size_t i) const { return {v[i], rho[i]}; }
    void fluid(const Particle& pi, const Pair& q, Sum& sum) const {
        sum += (2 * m * q.W / (pi.rho + rho[q.j])) * (v[q.j] - pi.v);
    }
    void wall(const Particle& pi, const WallPair& q, Sum& sum) const {
        sum += (q.mass() * q.W / pi.rho) * (q.src.vViscous[q.j] - pi.v);
    }
};

class TemplateViscosity final : public ViscosityModel {
public:
    explicit TemplateViscosity(const ModelContext& c) : c_(c.dict.getOrDefault<Scalar>("c", 0.01)) {}

    ResultKind result() const override { return ResultKind::velocityChange; }

    void addAcceleration(Scene& s, ParticleSystem& fluid, const Step& step) override {
        if (!(step.dt > 0)) return;
        const Scalar scale = c_ / step.dt;
        auto& a = fluid.particles.acceleration();
        const SmoothingTerm term{fluid.particles.velocity().data(), fluid.particles.density().data(),
                                 fluid.particles.particleMass()};
        forEachPairSum(s, fluid, fluid.particles.position(), term,
                       [&](std::size_t i, const auto&, const Vec3& dv) { a[i] += scale * dv; });
    }
    // the forces on walls and bodies: the reactions of the term's boundary pairs, a_ib = scale ×
    // its wall part (a forces function object reports them as viscous)
    void addReactions(const Scene& s, const ParticleSystem& fluid, const Step& step, Reactions& r) const override {
        if (!(step.dt > 0)) return;
        const SmoothingTerm term{fluid.particles.velocity().data(), fluid.particles.density().data(),
                                 fluid.particles.particleMass()};
        addScaledReactions(s, fluid, term, c_ / step.dt, ForceKind::viscous, r);
    }

private:
    Scalar c_;
};
} // namespace

SPINDRIFT_PLUGIN(ViscosityModel, TemplateViscosity)
