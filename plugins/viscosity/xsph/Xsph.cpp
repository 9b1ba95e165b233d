// xsph — XSPH velocity smoothing (Monaghan 1989; the viscosity of position-based fluids,
// Macklin & Müller 2013; MODELS.md "Viscosity"): each step pulls a particle's velocity towards
// its neighbourhood's,
//   Δv_i = c Σ_j (m_j / ρ̄_ij) (v_j − v_i) W_ij,   ρ̄_ij = (ρ_i + ρ_j)/2,
// returned as the acceleration Δv_i/Δt, so a symplectic-Euler step applies exactly Δv_i (with
// the velocities at the start of the step; PBF applies it after the position update).
// The pair term is symmetric in i, j with an antisymmetric velocity difference: momentum is
// conserved to round-off and kinetic energy decreases. Walls (wallFactor > 0): particles at
// rest with the fluid particle's density; the default 0 smooths among fluid particles only,
// as PBF does.
//
//   viscosity { type xsph; c 0.01; wallFactor 0; }
#include "Plugin.hpp"
#include "SphOperators.hpp"
#include "ViscosityModel.hpp"

namespace {
using namespace spindrift;

class Xsph final : public ViscosityModel {
public:
    explicit Xsph(const ModelContext& c)
        : c_(c.dict.getOrDefault<double>("c", 0.01)), wallFactor_(c.dict.getOrDefault<double>("wallFactor", 0.0)) {
        if (!(c_ >= 0 && c_ <= 1)) throw InputError(c.dict.locationOf("c"), "c must be in [0, 1]", "c");
        if (wallFactor_ < 0)
            throw InputError(c.dict.locationOf("wallFactor"), "wallFactor must not be negative", "wallFactor");
    }

    void addAcceleration(SphSystem& s, Scalar dt) override {
        if (!(dt > 0) || c_ == 0) return;
        const auto& kt = s.kernel;
        const Scalar m = s.fluid.particleMass();
        const auto& x = s.fluid.position();
        const auto& v = s.fluid.velocity();
        const auto& rho = s.fluid.density();
        auto& a = s.fluid.acceleration();
        const auto& xb = s.boundary.position();
        const Scalar* psi = s.boundaryMass ? s.boundaryMass->data() : nullptr;
        const Scalar scale = c_ / dt, wall = wallFactor_;
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < x.size(); ++i) {
            Vec3 acc = Vec3::Zero();
            forEachNeighbour(s.search.fluidNeighbours(), x, x, i, [&](Index j, const Vec3&, Scalar r2) {
                acc += (2 * m * kt.WSq(r2) / (rho[i] + rho[j])) * (v[j] - v[i]);
            });
            if (psi && wall != 0)
                forEachNeighbour(s.search.boundaryNeighbours(), x, xb, i, [&](Index b, const Vec3&, Scalar r2) {
                    acc -= (wall * psi[b] * kt.WSq(r2) / rho[i]) * v[i];
                });
            a[i] += scale * acc;
        }
    }

private:
    Scalar c_, wallFactor_;
};
} // namespace

SPINDRIFT_PLUGIN(ViscosityModel, Xsph)
