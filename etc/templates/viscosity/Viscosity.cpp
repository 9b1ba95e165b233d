// Template viscosity plugin: XSPH velocity smoothing among fluid particles,
// Δv_i = c Σ_j (2 m / (ρ_i + ρ_j)) (v_j − v_i) W_ij, returned as the acceleration Δv_i/Δt.
//   sphSchemes:  viscosity { type <this folder's name>; c 0.01; }
#include "Plugin.hpp"
#include "SphOperators.hpp"
#include "ViscosityModel.hpp"

namespace {
using namespace spindrift;

class TemplateViscosity final : public ViscosityModel {
public:
    explicit TemplateViscosity(const ModelContext& c) : c_(c.dict.getOrDefault<Scalar>("c", 0.01)) {}

    void addAcceleration(SphSystem& s, Scalar dt) override {
        if (!(dt > 0)) return;
        const auto& x = s.fluid.position();
        const auto& v = s.fluid.velocity();
        const auto& rho = s.fluid.density();
        auto& a = s.fluid.acceleration();
        const Scalar m = s.fluid.particleMass();
        for (std::size_t i = 0; i < x.size(); ++i) {
            Vec3 dv = Vec3::Zero();
            forEachNeighbour(s.search.fluidNeighbours(), x, x, i, [&](Index j, const Vec3&, Scalar r2) {
                dv += (2 * m * s.kernel.WSq(r2) / (rho[i] + rho[j])) * (v[j] - v[i]);
            });
            a[i] += (c_ / dt) * dv;
        }
    }

private:
    Scalar c_;
};
} // namespace

SPINDRIFT_PLUGIN(ViscosityModel, TemplateViscosity)
