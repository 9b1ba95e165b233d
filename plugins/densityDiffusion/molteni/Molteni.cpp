// molteni — density diffusion of Molteni & Colagrossi (2009), Comput. Phys. Commun. 180(6),
// 861–872, doi:10.1016/j.cpc.2008.12.004; docs/MODELS.md §molteni. In the continuity equation
//   dρ_i/dt += δ h c0 Σ_j V_j (ρ_i − ρ_j) (r_ij·∇_i W_ij) / (r² + 0.01 h²),   V_j = m/ρ_j,
// h the support radius (= 2 h_s: the paper's 2δ h_s c0 with ψ_ij = 2(ρ_i − ρ_j) r_ij/r²), c0 the
// sound speed, fluid pairs only. The denser of two particles loses density to the other: it damps
// the pressure noise of weakly compressible SPH. In a column at rest ρ grows with depth, so the
// term moves mass downwards forever (not hydrostatically consistent): antuono or fourtakas are.
//
//   densityDiffusion { type molteni; delta 0.1; }
#include "DensityDiffusion.hpp"
#include "PairLoop.hpp"
#include "Plugin.hpp"

namespace {
using namespace spindrift;

struct MolteniTerm {
    using Sum = Scalar;
    static constexpr bool usesDampedGradient = true; // (r_ij·∇W_ij)/(r² + 0.01 h²) = r² q.dampedGradFactor
    using Particle = Scalar; // ρ_i
    const Scalar* rho;
    const Scalar* invRho; // 1/ρ_j, taken once per particle (a division per pair less)
    Particle particle(std::size_t i) const { return rho[i]; }
    void fluid(Scalar rhoi, const Pair& q, Sum& sum) const {
        sum += (rhoi - rho[q.j]) * invRho[q.j] * q.r2 * q.dampedGradFactor;
    }
};

class Molteni final : public DensityDiffusion {
public:
    explicit Molteni(const ModelContext& c) : delta_(c.dict.getOrDefault<double>("delta", 0.1)) {
        if (!(delta_ >= 0)) throw InputError(c.dict.locationOf("delta"), "delta must not be negative", "delta");
    }

    void densityRate(const Scene& s, const ParticleSystem& fluid, std::vector<Scalar>& rate) const override {
        const Scalar h = s.constants.supportRadius;
        const Scalar scale = delta_ * h * s.constants.soundSpeed * fluid.particles.particleMass();
        continuityDensityRate(s, fluid, rate, MolteniTerm{fluid.particles.density().data(), inverseDensity(fluid)}, scale);
    }

private:
    Scalar delta_;
};
} // namespace

SPINDRIFT_PLUGIN(DensityDiffusion, Molteni)
