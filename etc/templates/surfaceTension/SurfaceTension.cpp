// Template surfaceTension plugin: a cohesion that pulls each fluid particle toward its fluid
// neighbours, in the form of Becker & Teschner (2007), a_i = −(σ/(ρ0 h³)) Σ_j V_j W_ij r_ij with
// r_ij = x_i − x_j. Not calibrated: σ sets its strength, not a Laplace pressure (the core's base
// class reads σ and limits the step by the capillary condition).
//   sphSchemes:  surfaceTension { type <this folder's name>; sigma 0.0728; }
#include "PairLoop.hpp"
#include "Plugin.hpp"
#include "SurfaceTensionModel.hpp"

namespace {
using namespace spindrift;

// Σ_j V_j W_ij r_ij over the particle's own fluid
struct CohesionTerm {
    using Sum = Vec3;
    static constexpr bool usesKernel = true;
    struct Particle {};
    const Scalar* rho;
    Scalar m;
    Particle particle(std::size_t) const { return {}; }
    void fluid(const Particle&, const Pair& q, Sum& sum) const { sum += (m / rho[q.j]) * q.W * q.r; }
};

class TemplateSurfaceTension final : public SurfaceTensionModel {
public:
    explicit TemplateSurfaceTension(const ModelContext& c) : SurfaceTensionModel(c) {}

    void addAcceleration(Scene& s, ParticleSystem& fluid, const Step&) override {
        const Scalar h = s.constants.supportRadius, scale = sigma() / (s.physics.rho0 * h * h * h);
        auto& a = fluid.particles.acceleration();
        forEachPairSum(s, fluid, fluid.particles.position(),
                       CohesionTerm{fluid.particles.density().data(), fluid.particles.particleMass()},
                       [&](std::size_t i, const auto&, const Vec3& sum) { a[i] -= scale * sum; });
    }

    // no boundary term: no force on a wall or body
    void addReactions(const Scene&, const ParticleSystem&, const Step&, Reactions&) const override {}
};
} // namespace

SPINDRIFT_PLUGIN(SurfaceTensionModel, TemplateSurfaceTension)
