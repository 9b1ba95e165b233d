// Template force plugin: a uniform body acceleration added to every particle of a fluid (the
// core calls it for each fluid system of the case).
//   sphSchemes:  forces { push { type <this folder's name>; acceleration (0.1 0 0); } }
#include "Plugin.hpp"
#include "ViscosityModel.hpp"

namespace {
using namespace spindrift;

class TemplateForce final : public ExtraForce {
public:
    explicit TemplateForce(const ModelContext& c) : acceleration_(c.dict.get<Vec3>("acceleration")) {}

    void addAcceleration(Scene&, ParticleSystem& fluid, const Step&) override {
        auto& a = fluid.particles.acceleration();
        forEachIndex(fluid.ownedSize(), [&](std::size_t i) { a[i] += acceleration_; });
    }

    // a body force has no boundary pair: no force on a wall or body
    void addReactions(const Scene&, const ParticleSystem&, const Step&, Reactions&) const override {}

private:
    Vec3 acceleration_;
};
} // namespace

SPINDRIFT_PLUGIN(ExtraForce, TemplateForce)
