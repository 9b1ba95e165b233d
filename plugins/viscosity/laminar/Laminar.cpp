// laminar — physical viscosity of Morris, Fox & Zhu (1997), docs/MODELS.md §laminar:
// a_i = Σ_j m_j (μ_i + μ_j) (r_ij·∇_i W_ij) / (ρ_i ρ_j (r² + 0.01h²)) v_ij,  μ = ρ ν,
// ν from constant/fluidProperties (or `nu` here). Walls: their particles with mass M_b, the
// wall's density (or the fluid particle's, where the boundary mirrors it) and the velocity the
// boundary model gives viscous terms — Adami's extrapolation makes the wall no-slip (Poiseuille
// plates do not slip); wallFactor 0 = free slip. Pairwise antisymmetric among fluid particles.
//
//   viscosity { type laminar; wallFactor 1; }
#include "PairLoop.hpp"
#include "Plugin.hpp"
#include "ViscosityModel.hpp"

namespace {
using namespace spindrift;

// (μ_i + μ_j)/(ρ_i ρ_j) r² F(r²)/(r² + ε) (v_i − v_j), F = (dW/dr)/r; m and ν applied after.
struct LaminarTerm {
    using Sum = Vec3;
    struct Particle {
        Vec3 v;
        Scalar rho;
    };
    const KernelTable& kt;
    const Vec3* v;
    const Scalar* rho;
    Scalar m, eps, wallFactor;
    bool visitsWalls;
    Particle particle(std::size_t i) const { return {v[i], rho[i]}; }
    Scalar shape(Scalar r2) const { return r2 * kt.gradFactorSq(r2) / (r2 + eps); }
    void fluid(const Particle& pi, const Pair& q, Sum& sum) const {
        sum += (m * (pi.rho + rho[q.j]) / (pi.rho * rho[q.j]) * shape(q.r2)) * (pi.v - v[q.j]);
    }
    void wall(const Particle& pi, const WallPair& q, Sum& sum) const {
        const Scalar rhob = q.wall.mirrored ? pi.rho : q.wall.rho[q.j];
        sum += (wallFactor * q.mass() * (pi.rho + rhob) / (pi.rho * rhob) * shape(q.r2)) * (pi.v - q.wall.vViscous[q.j]);
    }
};

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

    void addAcceleration(Scene& s, Scalar) override {
        const Scalar h = s.constants.supportRadius, nu = nu_;
        auto& a = s.fluid.acceleration();
        const LaminarTerm term{s.kernel, s.fluid.velocity().data(), s.fluid.density().data(), s.fluid.particleMass(),
                               Scalar(0.01) * h * h, wallFactor_, wallFactor_ != 0};
        forEachPairSum(s, s.fluid.position(), term, [&](std::size_t i, const auto&, const Vec3& sum) { a[i] += nu * sum; });
    }

private:
    Scalar nu_, wallFactor_;
};
} // namespace

SPINDRIFT_PLUGIN(ViscosityModel, Laminar)
