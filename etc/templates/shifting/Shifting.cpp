// Template shifting plugin: Fickian particle shifting (Lind et al. 2012) without free-surface
// treatment, a pair term on the core's pair loop (libsrc/PairLoop.hpp): particles move with
// v + δv, δv_i = −(D/Δt) Σ_j (m/ρ_j) ∇_i W_ij, D = coefficient · h², down the gradient of the
// particle concentration, so the distribution stays regular (for flows without a free surface).
//   sphSchemes:  shifting { type <this folder's name>; coefficient 0.01; }
#include "PairLoop.hpp"
#include "Plugin.hpp"
#include "ShiftingModel.hpp"

namespace {
using namespace spindrift;

struct ConcentrationGradientTerm {
    using Sum = Vec3;
    static constexpr bool usesGradient = true;
    struct Particle {};
    const Scalar* rho;
    Scalar m;
    Particle particle(std::size_t) const { return {}; }
    void fluid(const Particle&, const Pair& q, Sum& sum) const { sum += (m / rho[q.j]) * q.gradW; }
    void wall(const Particle&, const WallPair& q, Sum& sum) const { sum += (q.mass() / q.src.rho[q.j]) * q.gradW; }
};

class TemplateShifting final : public ShiftingModel {
public:
    explicit TemplateShifting(const ModelContext& c) : coefficient_(c.dict.getOrDefault<Scalar>("coefficient", 0.01)) {}

    void computeShift(Scene& s, ParticleSystem& fluid, const Step& step) override {
        auto& shift = *fluid.particles.findVector("shiftingVelocity"); // the core registered it
        const Scalar h = s.constants.supportRadius, scale = -coefficient_ * h * h / step.dt;
        const ConcentrationGradientTerm term{fluid.particles.density().data(), fluid.particles.particleMass()};
        forEachPairSum(s, fluid, fluid.particles.position(), term,
                       [&](std::size_t i, const auto&, const Vec3& gradC) { shift[i] = scale * gradC; });
    }

    // it only shifts (adds no acceleration): no force on a wall or body
    void addReactions(const Scene&, const ParticleSystem&, const Step&, Reactions&) const override {}

private:
    Scalar coefficient_;
};
} // namespace

SPINDRIFT_PLUGIN(ShiftingModel, TemplateShifting)
