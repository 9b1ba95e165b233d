// A boundary model whose walls have a pressure and density of their own (not mirrored from the
// fluid, as Adami et al. 2012), for the output tests (tests/unit/WallOutputTest.cpp): every wall
// particle has the mass of a fluid particle, the pressure `wallPressure` and the rest density.
//   sphSchemes:  boundary { type ownPressure; wallPressure 1234; }
#include "BoundaryModel.hpp"
#include "Plugin.hpp"

#include <algorithm>

namespace {
using namespace spindrift;

class OwnPressureBoundary final : public BoundaryModel {
public:
    explicit OwnPressureBoundary(const ModelContext& c) : pressure_(c.dict.get<Scalar>("wallPressure")) {}

    void initialise(Scene& s) override {
        for (ParticleSystem* w : s.boundaries()) {
            auto& mass = w->particles.addScalar("wallMass", {false, false});
            std::fill(mass.begin(), mass.end(), s.constants.particleMass);
            w->mass = &mass;
            w->pressureMirrored = false;
        }
    }
    void update(Scene& s, const Step&) override {
        for (ParticleSystem* w : s.boundaries()) {
            std::fill(w->particles.pressure().begin(), w->particles.pressure().end(), pressure_);
            std::fill(w->particles.density().begin(), w->particles.density().end(), s.constants.rho0);
        }
    }

private:
    Scalar pressure_;
};
} // namespace

SPINDRIFT_PLUGIN(BoundaryModel, OwnPressureBoundary)
