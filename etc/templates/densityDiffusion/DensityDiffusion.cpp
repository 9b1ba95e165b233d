// Template density-diffusion plugin: Molteni & Colagrossi's term in the continuity equation, a
// pair term on the core's pair loop (libsrc/PairLoop.hpp):
//   dρ_i/dt += δ h c0 Σ_j (m/ρ_j) (ρ_i − ρ_j) (r_ij·∇_i W_ij) / (r² + 0.01 h²)
// It acts on a density integrated in time (a pressure model with `density continuity;`).
//   sphSchemes:  densityDiffusion { type <this folder's name>; delta 0.1; }
#include "DensityDiffusion.hpp"
#include "PairLoop.hpp"
#include "Plugin.hpp"

namespace {
using namespace spindrift;

struct DiffusionTerm {
    using Sum = Scalar;
    static constexpr bool usesGradient = true;
    using Particle = Scalar; // ρ_i
    const Scalar* rho;
    Scalar eps;
    Particle particle(std::size_t i) const { return rho[i]; }
    void fluid(Scalar rhoi, const Pair& q, Sum& sum) const {
        sum += (rhoi - rho[q.j]) / rho[q.j] * q.r.dot(q.gradW) / (q.r2 + eps);
    }
};

class TemplateDensityDiffusion final : public DensityDiffusion {
public:
    explicit TemplateDensityDiffusion(const ModelContext& c) : delta_(c.dict.getOrDefault<Scalar>("delta", 0.1)) {}

    // the continuity equation's rate with the term added, both in one pass over the pairs
    void densityRate(const Scene& s, const ParticleSystem& fluid, std::vector<Scalar>& rate) const override {
        const Scalar h = s.constants.supportRadius;
        const Scalar scale = delta_ * h * s.constants.soundSpeed * fluid.particles.particleMass();
        continuityDensityRate(s, fluid, rate, DiffusionTerm{fluid.particles.density().data(), Scalar(0.01) * h * h},
                              scale);
    }

private:
    Scalar delta_;
};
} // namespace

SPINDRIFT_PLUGIN(DensityDiffusion, TemplateDensityDiffusion)
