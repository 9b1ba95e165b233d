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

    void computeDensity(Scene& s) override {
        auto& rho = s.fluid.density();
        auto& p = s.fluid.pressure();
        summationDensity(s, s.fluid.position(), rho);
        for (std::size_t i = 0; i < rho.size(); ++i) p[i] = c0_ * c0_ * (rho[i] - rho0_);
    }

    void addPressureAcceleration(Scene& s, Scalar) override { addSymmetricPressureAcceleration(s, pOverRho2_); }

private:
    Scalar c0_, rho0_;
    std::vector<Scalar> pOverRho2_;
};
} // namespace

SPINDRIFT_PLUGIN(PressureModel, TemplatePressure)
