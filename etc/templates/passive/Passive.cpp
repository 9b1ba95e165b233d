// Template passive plugin: tracers, particles carried with the fluid's velocity interpolated at
// their positions (Shepard: v(x) = Σ_j V_j v_j W(x − x_j) / Σ_j V_j W(x − x_j), V_j = m_j/ρ_j),
// seeded on a lattice in a box. They never act on the fluid; the core searches, writes
// (<name>.vtp, a block of its own), restarts and rolls them back as every other system.
//   sphSchemes:  passive { tracers { type <this folder's name>; min (0.1 0.1 0); max (0.2 0.2 0);
//                                   spacing 0.02; } }
#include "PairLoop.hpp"
#include "PassiveModel.hpp"
#include "Plugin.hpp"

namespace {
using namespace spindrift;

// Σ_j V_j v_j W_ij and Σ_j V_j W_ij over the fluid around a tracer (read through the pair's
// source: the tracers' neighbours are another system's).
struct ShepardVelocityTerm {
    struct Sum {
        Vec3 v = Vec3::Zero();
        Scalar w = 0;
    };
    static constexpr bool usesKernel = true, visitsOtherFluids = true;
    struct Particle {};
    Particle particle(std::size_t) const { return {}; }
    void fluid(const Particle&, const Pair& p, Sum& sum) const {
        const Scalar w = p.src.particleMass / p.src.rho[p.j] * p.W;
        sum.v += w * p.src.v[p.j];
        sum.w += w;
    }
};

class TemplatePassive final : public PassiveModel {
public:
    explicit TemplatePassive(const ModelContext& c)
        : name_(c.name), min_(c.dict.get<Vec3>("min")), max_(c.dict.get<Vec3>("max")),
          spacing_(c.dict.get<Scalar>("spacing")), dimension_(c.physics.dimension) {
        if (!(spacing_ > 0)) throw InputError(c.dict.locationOf("spacing"), "spacing must be positive", "spacing");
    }

    void initialise(Scene& s) override {
        ParticleSystem& tracers = s.addSystem(name_, SystemRole::passive);
        auto& set = tracers.particles;
        for (Scalar z = min_[2] + spacing_ / 2; dimension_ == 2 ? z == min_[2] + spacing_ / 2 : z < max_[2]; z += spacing_)
            for (Scalar y = min_[1] + spacing_ / 2; y < max_[1]; y += spacing_)
                for (Scalar x = min_[0] + spacing_ / 2; x < max_[0]; x += spacing_)
                    set.append(Vec3(x, y, dimension_ == 2 ? Scalar(0) : z), Vec3::Zero(), Index(set.size()));
        s.registerWithSearch(tracers);
        for (const ParticleSystem* fluid : s.ofRole(SystemRole::fluid)) s.search.addInteraction(tracers.index, fluid->index);
        index_ = tracers.index;
    }

    // v = the fluid's interpolated velocity, x += Δt v (tracers outside the fluid stand still)
    void afterStep(Scene& s, const Step& step) override {
        ParticleSystem& tracers = s.system(index_);
        auto& x = tracers.particles.position();
        auto& v = tracers.particles.velocity();
        forEachPairSum(s, tracers, x, ShepardVelocityTerm{}, [&](std::size_t i, const auto&, const auto& sum) {
            v[i] = sum.w > 0 ? Vec3(sum.v / sum.w) : Vec3::Zero();
        });
        forEachIndex(tracers.ownedSize(), [&](std::size_t i) { x[i] += step.dt * v[i]; });
        step.core.wrap(s, tracers, x);
    }

private:
    std::string name_;
    Vec3 min_, max_;
    Scalar spacing_;
    int dimension_;
    std::size_t index_ = 0;
};
} // namespace

SPINDRIFT_PLUGIN(PassiveModel, TemplatePassive)
