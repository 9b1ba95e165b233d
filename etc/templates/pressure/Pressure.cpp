// Template pressure plugin: weakly compressible SPH with a linear equation of state
// p = c0² (ρ − ρ0), summation density and the symmetric pressure gradient of the core's pair
// loop (libsrc/PairLoop.hpp; walls take part with the masses their boundary model gives them).
//   sphSchemes:  pressure { type <this folder's name>; soundSpeed 25; }
#include "PairLoop.hpp"
#include "Plugin.hpp"
#include "PressureModel.hpp"

namespace {
using namespace spindrift;

class TemplatePressure final : public PressureModel {
public:
    explicit TemplatePressure(const ModelContext& c)
        : c0_(c.dict.get<Scalar>("soundSpeed")), rho0_(c.physics.rho0) {}

    // declared at set-up: artificial viscosity and the time-step limit read it (Scene::constants)
    Scalar soundSpeed(const SceneConstants&, const PhysicalParameters&) const override { return c0_; }

    void computeDensity(Scene& s, ParticleSystem& fluid, const Step&) override {
        auto& rho = fluid.particles.density();
        auto& p = fluid.particles.pressure();
        summationDensity(s, fluid, fluid.particles.position(), rho);
        forEachIndex(rho.size(), [&](std::size_t i) { p[i] = c0_ * c0_ * (rho[i] - rho0_); });
    }

    void addPressureAcceleration(Scene& s, ParticleSystem& fluid, const Step&) override {
        addSymmetricPressureAcceleration(s, fluid, pOverRho2_);
    }
    // the forces on walls and bodies (a forces function object, a floating body): the reactions
    // of the pressure term's boundary pairs, with the p/ρ² of the last pass
    void addReactions(const Scene& s, const ParticleSystem& fluid, const Step&, Reactions& r) const override {
        addSymmetricPressureReactions(s, fluid, fluid.particles.position(), pOverRho2_.data(), r);
    }

private:
    Scalar c0_, rho0_;
    std::vector<Scalar> pOverRho2_;
};
} // namespace

SPINDRIFT_PLUGIN(PressureModel, TemplatePressure)
