// Template boundary plugin: every particle of a boundary (a wall or a body) weighs as a fluid
// particle (walls sampled on the fluid lattice) and mirrors the pressure of the fluid particle it
// meets; fluid particles that would cross a wall's face collide with it (BoundaryModel's
// collision_, WallCollision.hpp: on by default, `collision { restitution 0.5; }`, `collision no;`).
//   sphSchemes:  boundary { type <this folder's name>; }
#include "BoundaryModel.hpp"
#include "Plugin.hpp"

#include <algorithm>

namespace {
using namespace spindrift;

class TemplateBoundary final : public BoundaryModel {
public:
    explicit TemplateBoundary(const ModelContext& c) { collision_.read(c.dict); }

    void initialise(Scene& s) override {
        collision_.initialise(s);
        for (ParticleSystem* w : s.boundaries()) { // a system per constant/geometry walls or bodies entry
            auto& mass = w->particles.addScalar("wallMass");
            std::fill(mass.begin(), mass.end(), s.constants.particleMass);
            w->mass = &mass;
            w->pressureMirrored = true;
        }
    }
};
} // namespace

SPINDRIFT_PLUGIN(BoundaryModel, TemplateBoundary)
