// Template pressure plugin: weakly compressible SPH with a linear equation of state
// p = c0² (ρ − ρ0), summation density and the symmetric pressure gradient (SphOperators.hpp).
//   sphSchemes:  pressure { type <this folder's name>; soundSpeed 25; }
#include "Plugin.hpp"
#include "PressureModel.hpp"
#include "SphOperators.hpp"

namespace {
using namespace spindrift;

class TemplatePressure final : public PressureModel {
public:
    explicit TemplatePressure(const ModelContext& c)
        : c0_(c.dict.get<Scalar>("soundSpeed")), rho0_(c.physics.rho0) {}

    void computeDensity(SphSystem& s) override {
        auto& rho = s.fluid.density();
        auto& p = s.fluid.pressure();
        summationDensity(s, s.fluid.position(), rho);
        for (std::size_t i = 0; i < rho.size(); ++i) p[i] = c0_ * c0_ * (rho[i] - rho0_);
    }

    void addPressureAcceleration(SphSystem& s, Scalar) override {
        addSymmetricPressureAcceleration(s, s.fluid.position(), s.fluid.pressure(), s.fluid.density(),
                                         s.fluid.acceleration(), WallMasses::ofBoundaryModel(s), pOverRho2_);
    }

    Scalar soundSpeed() const override { return c0_; }

private:
    Scalar c0_, rho0_;
    std::vector<Scalar> pOverRho2_;
};
} // namespace

SPINDRIFT_PLUGIN(PressureModel, TemplatePressure)
