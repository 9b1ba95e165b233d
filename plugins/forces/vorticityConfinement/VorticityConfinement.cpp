// vorticityConfinement — vorticity confinement for particle fluids (Macklin & Müller 2013,
// eqs. 15–16; used by seed 002 §5 with any pressure solver; docs/MODELS.md §vorticityConfinement):
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
#include "PairLoop.hpp"
#include "ViscosityModel.hpp"

#include <Eigen/Geometry>

namespace {
using namespace spindrift;

// ω_i = Σ_j V_j (v_i − v_j) × ∇_i W_ij
struct CurlTerm {
    using Sum = Vec3;
    static constexpr bool usesGradient = true;
    using Particle = Vec3; // v_i
    const Vec3* v;
    const Scalar* rho;
    Scalar m;
    Particle particle(std::size_t i) const { return v[i]; }
    void fluid(const Vec3& vi, const Pair& q, Sum& sum) const { sum += (m / rho[q.j]) * (vi - v[q.j]).cross(q.gradW); }
};

// η_i = Σ_j V_j (|ω_j| − |ω_i|) ∇_i W_ij
struct VorticityGradientTerm {
    using Sum = Vec3;
    static constexpr bool usesGradient = true;
    using Particle = Scalar; // |ω_i|
    const Vec3* omega;
    const Scalar* rho;
    Scalar m;
    Particle particle(std::size_t i) const { return omega[i].norm(); }
    void fluid(Scalar wi, const Pair& q, Sum& sum) const { sum += ((m / rho[q.j]) * (omega[q.j].norm() - wi)) * q.gradW; }
};

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

    void initialise(Scene& s) override {
        for (ParticleSystem* fluid : s.ofRole(SystemRole::fluid)) fluid->particles.addVector("vorticity", {true, false});
    }

    void addAcceleration(Scene& s, ParticleSystem& fluid, const Step&) override {
        const Scalar m = fluid.particles.particleMass(), h = s.constants.supportRadius, eps = epsilon_;
        const auto& x = fluid.particles.position();
        const Scalar* rho = fluid.particles.density().data();
        auto& w = *fluid.particles.findVector("vorticity");
        forEachPairSum(s, fluid, x, CurlTerm{fluid.particles.velocity().data(), rho, m},
                       [&](std::size_t i, const auto&, const Vec3& curl) { w[i] = curl; });
        if (epsilon_ == 0) return;
        auto& a = fluid.particles.acceleration();
        forEachPairSum(s, fluid, x, VorticityGradientTerm{w.data(), rho, m}, [&](std::size_t i, Scalar wi, const Vec3& eta) {
            // N = η/|η| is undefined where |ω| is uniform: a gradient below 1e-6 |ω_i|/h is
            // round-off, not a direction
            const Scalar len = eta.norm();
            if (wi > 0 && len * h > Scalar(1e-6) * wi) a[i] += eps * (eta / len).cross(w[i]);
        });
    }

    // its terms have no boundary part: no force on a wall or body
    void addReactions(const Scene&, const ParticleSystem&, const Step&, Reactions&) const override {}

private:
    Scalar epsilon_ = 0;
};
} // namespace

SPINDRIFT_PLUGIN(ExtraForce, VorticityConfinement)
