// fourtakas — density diffusion with the hydrostatic correction of Fourtakas et al. (2019),
// Comput. Fluids 190, 346–361, doi:10.1016/j.compfluid.2019.06.009 (DualSPHysics' "DDT
// Fourtakas"); docs/MODELS.md §fourtakas. Molteni & Colagrossi's term on the dynamic part of the
// density difference only:
//   dρ_i/dt += δ h c0 Σ_j V_j [(ρ_i − ρ_j) + ρ^H_ji] (r_ij·∇_i W_ij) / (r² + 0.01 h²),
//   ρ^H_ji = ρ0 [(1 − ρ0 g·r_ij / B)^(1/γ) − 1] ≈ −ρ0 g·r_ij / c0²,   B = c0² ρ0/γ,
// the hydrostatic density of j relative to i (j a height −g·r_ij/|g| below: denser), to first
// order in ρ0 |g| r / B (below 1e-3 within a support; DualSPHysics takes the power, a call per
// pair). A column at rest, whose density is hydrostatic, has nothing to diffuse. Fluid pairs only (as DualSPHysics'
// full variant, and TrixiParticles). h the support radius (= 2 h_s).
//
//   densityDiffusion { type fourtakas; delta 0.1; }
#include "DensityDiffusion.hpp"
#include "PairLoop.hpp"
#include "Plugin.hpp"

namespace {
using namespace spindrift;

struct FourtakasTerm {
    using Sum = Scalar;
    static constexpr bool usesDampedGradient = true; // (r_ij·∇W_ij)/(r² + 0.01 h²) = r² q.dampedGradFactor
    using Particle = Scalar; // ρ_i
    const Scalar* rho;
    const Scalar* invRho; // 1/ρ_j, taken once per particle (a division per pair less)
    Vec3 hydrostatic; // −ρ0 g / c0²: ρ^H_ji = hydrostatic · r_ij
    Particle particle(std::size_t i) const { return rho[i]; }
    void fluid(Scalar rhoi, const Pair& q, Sum& sum) const {
        sum += (rhoi - rho[q.j] + hydrostatic.dot(q.r)) * invRho[q.j] * q.r2 * q.dampedGradFactor;
    }
};

class Fourtakas final : public DensityDiffusion {
public:
    explicit Fourtakas(const ModelContext& c) : delta_(c.dict.getOrDefault<double>("delta", 0.1)) {
        if (!(delta_ >= 0)) throw InputError(c.dict.locationOf("delta"), "delta must not be negative", "delta");
    }

    void initialise(Scene& s) override {
        if (!(s.constants.soundSpeed > 0))
            throw std::runtime_error("densityDiffusion fourtakas needs the sound speed of a weakly compressible "
                                     "pressure model (wcsph, isobaric)");
    }

    void densityRate(const Scene& s, const ParticleSystem& fluid, std::vector<Scalar>& rate) const override {
        const SceneConstants& c = s.constants;
        const Scalar h = c.supportRadius;
        const Scalar scale = delta_ * h * c.soundSpeed * fluid.particles.particleMass();
        const FourtakasTerm term{fluid.particles.density().data(), inverseDensity(fluid),
                                 Vec3(-fluid.rho0 * s.physics.gravity / (c.soundSpeed * c.soundSpeed))};
        continuityDensityRate(s, fluid, rate, term, scale);
    }

private:
    Scalar delta_;
};
} // namespace

SPINDRIFT_PLUGIN(DensityDiffusion, Fourtakas)
