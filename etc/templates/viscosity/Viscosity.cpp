// Template viscosity plugin: XSPH velocity smoothing, a pair term on the core's pair loop
// (libsrc/PairLoop.hpp), which visits every fluid neighbour j and every wall particle b of each
// fluid particle i in the balanced parallel schedule:
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
        sum += (q.mass() * q.W / pi.rho) * (q.wall.vViscous[q.j] - pi.v);
    }
};

class TemplateViscosity final : public ViscosityModel {
public:
    explicit TemplateViscosity(const ModelContext& c) : c_(c.dict.getOrDefault<Scalar>("c", 0.01)) {}

    ResultKind result() const override { return ResultKind::velocityChange; }

    void addAcceleration(Scene& s, Scalar dt) override {
        if (!(dt > 0)) return;
        const Scalar scale = c_ / dt;
        auto& a = s.fluid.acceleration();
        const SmoothingTerm term{s.fluid.velocity().data(), s.fluid.density().data(), s.fluid.particleMass()};
        forEachPairSum(s, s.fluid.position(), term, [&](std::size_t i, const auto&, const Vec3& dv) { a[i] += scale * dv; });
    }

private:
    Scalar c_;
};
} // namespace

SPINDRIFT_PLUGIN(ViscosityModel, TemplateViscosity)
