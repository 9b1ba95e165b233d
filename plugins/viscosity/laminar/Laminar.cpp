// laminar — physical viscosity of Morris, Fox & Zhu (1997), docs/MODELS.md §laminar:
// a_i = Σ_j m_j (μ_i + μ_j) (r_ij·∇_i W_ij) / (ρ_i ρ_j (r² + 0.01h²)) v_ij,  μ = ρ ν,
// ν from constant/fluidProperties (or `nu` here). Walls: their particles with mass M_b, the
// wall's density (or the fluid particle's, where the boundary mirrors it) and the velocity the
// boundary model gives viscous terms — Adami's extrapolation makes the wall no-slip (Poiseuille
// plates do not slip); wallFactor 0 = free slip. Pairwise antisymmetric among fluid particles.
// latticeCorrection (yes): the sum is divided by its value for a quadratic velocity field on the
// initial lattice, Λ = Σ_k V0 (−W'(r_k)) r_k x_k²/(r_k² + 0.01h²) over the lattice offsets k
// (V0 = m/ρ0), as the particle mass makes summation density exact there. The 0.01h² (h the
// support radius) alone makes the sum 5.8 % too weak (the continuum value, any kernel width:
// Λ = 0.942 for Wendland C2), the lattice's second moment adds −2.1 % at a support of 2.6Δx
// (Λ = 0.921) and +0.3 % at 4Δx (Λ = 0.945): a viscosity that much too low (a Poiseuille flow
// 8 % too fast at steady state on adami walls at L/40). docs/MODELS.md §laminar.
//
//   viscosity { type laminar; wallFactor 1; latticeCorrection yes; }
#include "PairLoop.hpp"
#include "Plugin.hpp"
#include "ViscosityModel.hpp"

#include <cmath>

namespace {
using namespace spindrift;

// (μ_i + μ_j)/(ρ_i ρ_j) r² F(r²)/(r² + ε) (v_i − v_j), F = (dW/dr)/r; m and ν applied after.
struct LaminarTerm : VelocityDensityTerm {
    using Sum = Vec3;
    static constexpr bool usesDampedGradient = true; // r² F(r²)/(r² + ε) = r² q.dampedGradFactor
    Scalar m, wallFactor;
    bool visitsWalls;
    void fluid(const Particle& pi, const Pair& q, Sum& sum) const {
        sum += (m * (pi.rho + rho[q.j]) / (pi.rho * rho[q.j]) * q.r2 * q.dampedGradFactor) * (pi.v - v[q.j]);
    }
    void wall(const Particle& pi, const WallPair& q, Sum& sum) const {
        const Scalar rhob = q.src.mirrored ? pi.rho : q.src.rho[q.j];
        sum += (wallFactor * q.mass() * (pi.rho + rhob) / (pi.rho * rhob) * q.r2 * q.dampedGradFactor) *
               (pi.v - q.src.vViscous[q.j]);
    }
};

class Laminar final : public ViscosityModel {
public:
    explicit Laminar(const ModelContext& c)
        : nu_(c.dict.getOrDefault<double>("nu", c.physics.nu)),
          wallFactor_(c.dict.getOrDefault<double>("wallFactor", 1.0)),
          latticeCorrection_(c.dict.getOrDefault<bool>("latticeCorrection", true)) {
        if (!(nu_ > 0))
            throw InputError(c.dict.found("nu") ? c.dict.locationOf("nu") : c.dict.where(),
                             "laminar viscosity needs a positive kinematic viscosity ('viscosity' in "
                             "constant/fluidProperties or 'nu' here)", "nu");
    }

    // the viscous limit of the effective ν
    double maxTimeStep(const Scene& s, const StateSpeeds&) const override { return viscousTimeStepLimit(s, nu_ * correction_); }

    void initialise(Scene& s) override {
        const Scalar moment = latticeCorrection_ ? latticeSecondMoment(s) : Scalar(1);
        correction_ = moment > 0 ? 1 / moment : Scalar(1); // 0 without a particle mass (a bare test scene)
    }

    void addAcceleration(Scene& s, ParticleSystem& fluid, const Step&) override {
        const Scalar nu = nu_ * correction_;
        auto& a = fluid.particles.acceleration();
        forEachPairSum(s, fluid, fluid.particles.position(), termOf(fluid),
                       [&](std::size_t i, const auto&, const Vec3& sum) { a[i] += nu * sum; });
    }
    void addReactions(const Scene& s, const ParticleSystem& fluid, const Step&, Reactions& r) const override {
        addScaledReactions(s, fluid, termOf(fluid), nu_ * correction_, ForceKind::viscous, r);
    }

    // Λ = Σ_k V0 (−W'(r_k)) r_k x_k²/(r_k² + 0.01h²) over the offsets k ≠ 0 of the initial
    // lattice (spacing Δx, the case's dimension), V0 = m/ρ0: the sum's value for v = x² e/2
    // relative to the exact Laplacian e (1 for an exact quadrature, ε = 0).
    static Scalar latticeSecondMoment(const Scene& s) {
        const auto& kt = s.kernel;
        const double dx = s.physics.particleSpacing, h = s.constants.supportRadius;
        const double V0 = s.constants.particleMass / s.constants.rho0;
        const int reach = int(std::ceil(h / dx)), dim = s.physics.dimension;
        double sum = 0;
        for (int k = (dim == 3 ? -reach : 0); k <= (dim == 3 ? reach : 0); ++k)
            for (int j = -reach; j <= reach; ++j)
                for (int i = -reach; i <= reach; ++i) {
                    // (−W'/r) from the table the pair term reads, so the correction is exact on the lattice
                    const double x = i * dx, r2 = dx * dx * double(i * i + j * j + k * k);
                    if (r2 > 0 && r2 < h * h) sum += V0 * -kt.dampedGradFactorSq(Scalar(r2)) * r2 * x * x;
                }
        return Scalar(sum);
    }

private:
    LaminarTerm termOf(const ParticleSystem& fluid) const {
        return {{fluid.particles.velocity().data(), fluid.particles.density().data()}, fluid.particles.particleMass(),
                wallFactor_, wallFactor_ != 0};
    }

    Scalar nu_, wallFactor_;
    bool latticeCorrection_;
    Scalar correction_ = 1;
};
} // namespace

SPINDRIFT_PLUGIN(ViscosityModel, Laminar)
