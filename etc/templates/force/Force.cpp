// Template force plugin: a uniform body acceleration added to every fluid particle.
//   sphSchemes:  forces { push { type <this folder's name>; acceleration (0.1 0 0); } }
#include "Plugin.hpp"
#include "ViscosityModel.hpp"

namespace {
using namespace spindrift;

class TemplateForce final : public ExtraForce {
public:
    explicit TemplateForce(const ModelContext& c) : acceleration_(c.dict.get<Vec3>("acceleration")) {}

    void addAcceleration(Scene& s, Scalar) override {
        for (auto& a : s.fluid.acceleration()) a += acceleration_;
    }

private:
    Vec3 acceleration_;
};
} // namespace

SPINDRIFT_PLUGIN(ExtraForce, TemplateForce)
