// laminar — physical viscosity of Morris, Fox & Zhu (1997), MODELS.md "Viscosity":
// a_i = Σ_j m_j (μ_i + μ_j) (r_ij·∇_i W_ij) / (ρ_i ρ_j (r² + 0.01h²)) v_ij,  μ = ρ ν,
// ν from constant/fluidProperties (or `nu` here). Walls: no-slip particles at rest with the
// fluid particle's density (wallFactor 0 = free slip). Pairwise antisymmetric.
//
//   viscosity { type laminar; wallFactor 1; }
#include "Plugin.hpp"
#include "SphOperators.hpp"
#include "ViscosityModel.hpp"

namespace {
using namespace spindrift;

class Laminar final : public ViscosityModel {
public:
    explicit Laminar(const ModelContext& c)
        : nu_(c.dict.getOrDefault<double>("nu", c.physics.nu)),
          wallFactor_(c.dict.getOrDefault<double>("wallFactor", 1.0)) {
        if (!(nu_ > 0))
            throw InputError(c.dict.found("nu") ? c.dict.locationOf("nu") : c.dict.where(),
                             "laminar viscosity needs a positive kinematic viscosity ('viscosity' in "
                             "constant/fluidProperties or 'nu' here)", "nu");
    }

    Scalar timeStepViscosity() const override { return nu_; }

    void addAcceleration(SphSystem& s, Scalar) override {
        const auto& kt = s.kernel;
        const Scalar m = s.fluid.particleMass(), h = kt.supportRadius(), eps = Scalar(0.01) * h * h;
        const auto& x = s.fluid.position();
        const auto& v = s.fluid.velocity();
        const auto& rho = s.fluid.density();
        auto& a = s.fluid.acceleration();
        const auto& xb = s.boundary.position();
        const Scalar* psi = s.boundaryMass ? s.boundaryMass->data() : nullptr;
        // μ_i + μ_j = ν(ρ_i + ρ_j) for one fluid
        const Scalar nu = nu_, wall = wallFactor_;
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < x.size(); ++i) {
            Vec3 acc = Vec3::Zero();
            forEachNeighbour(s.search.fluidNeighbours(), x, x, i, [&](Index j, const Vec3&, Scalar r2) {
                // r dW/dr = r² (dW/dr / r)
                const Scalar f = m * nu * (rho[i] + rho[j]) * r2 * kt.gradFactorSq(r2) / (rho[i] * rho[j] * (r2 + eps));
                acc += f * (v[i] - v[j]);
            });
            if (psi && wall != 0)
                forEachNeighbour(s.search.boundaryNeighbours(), x, xb, i, [&](Index b, const Vec3&, Scalar r2) {
                    acc += (wall * psi[b] * 2 * nu * r2 * kt.gradFactorSq(r2) / (rho[i] * (r2 + eps))) * v[i];
                });
            a[i] += acc;
        }
    }

private:
    Scalar nu_, wallFactor_;
};
} // namespace

SPINDRIFT_PLUGIN(ViscosityModel, Laminar)
