// vorticityConfinement — vorticity confinement for particle fluids (Macklin & Müller 2013,
// eqs. 15–16; used by seed 002 §5 with any pressure solver; MODELS.md "Later models"):
//   ω_i = ∇×v ≈ Σ_j V_j (v_i − v_j) × ∇_i W_ij,          V_j = m/ρ_j
//   η_i = ∇|ω|_i ≈ Σ_j V_j (|ω_j| − |ω_i|) ∇_i W_ij,     N_i = η_i/|η_i|
//   a_i = ε (N_i × ω_i)
// It puts back rotational energy that the numerical damping of large time steps removes.
// ε [m/s] sets the strength (Macklin & Müller's "ε (N × ω)", read as an acceleration so that ε
// has units of a velocity; a few percent of the flow speed is typical). Fluid neighbours only;
// the vorticity is written as the particle field `vorticity`.
//
//   forces { vorticity { type vorticityConfinement; epsilon 0.01; } }
#include "Plugin.hpp"
#include "SphOperators.hpp"
#include "ViscosityModel.hpp"

#include <Eigen/Geometry>

namespace {
using namespace spindrift;

class VorticityConfinement final : public ExtraForce {
public:
    explicit VorticityConfinement(const ModelContext& c) {
        if (!c.dict.found("epsilon"))
            throw InputError(c.dict.where(), "vorticityConfinement needs 'epsilon' (strength, m/s; e.g. 0.01)",
                             "epsilon");
        epsilon_ = c.dict.get<double>("epsilon");
        if (!(epsilon_ >= 0))
            throw InputError(c.dict.locationOf("epsilon"), "epsilon must not be negative", "epsilon");
    }

    void initialise(SphSystem& s) override { omega_ = &s.fluid.addVector("vorticity", {true, false}); }

    void addAcceleration(SphSystem& s, Scalar) override {
        const auto& kt = s.kernel;
        const Scalar m = s.fluid.particleMass();
        const auto& x = s.fluid.position();
        const auto& v = s.fluid.velocity();
        const auto& rho = s.fluid.density();
        const auto& ff = s.search.fluidNeighbours();
        auto& a = s.fluid.acceleration();
        auto& w = *omega_;
        const std::size_t n = x.size();
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < n; ++i) {
            Vec3 curl = Vec3::Zero();
            forEachNeighbour(ff, x, x, i, [&](Index j, const Vec3& rij, Scalar r2) {
                curl += (m / rho[j]) * (v[i] - v[j]).cross(kt.gradWSq(rij, r2));
            });
            w[i] = curl;
        }
        if (epsilon_ == 0) return;
        const Scalar eps = epsilon_, h = kt.supportRadius();
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < n; ++i) {
            const Scalar wi = w[i].norm();
            Vec3 eta = Vec3::Zero();
            forEachNeighbour(ff, x, x, i, [&](Index j, const Vec3& rij, Scalar r2) {
                eta += ((m / rho[j]) * (w[j].norm() - wi)) * kt.gradWSq(rij, r2);
            });
            // N = η/|η| is undefined where |ω| is uniform: a gradient below 1e-6 |ω_i|/h is
            // round-off, not a direction
            const Scalar len = eta.norm();
            if (wi > 0 && len * h > Scalar(1e-6) * wi) a[i] += eps * (eta / len).cross(w[i]);
        }
    }

private:
    Scalar epsilon_ = 0;
    std::vector<Vec3>* omega_ = nullptr;
};
} // namespace

SPINDRIFT_PLUGIN(ExtraForce, VorticityConfinement)
