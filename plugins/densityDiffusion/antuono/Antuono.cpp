// antuono — the density diffusion of δ-SPH, Antuono et al. (2010), Comput. Phys. Commun. 181(3),
// 532–549, doi:10.1016/j.cpc.2009.11.002 (as written up in Antuono, Colagrossi & Marrone 2012,
// doi:10.1016/j.cpc.2012.07.006); docs/MODELS.md §antuono. Molteni & Colagrossi's term less the
// part of the density difference a linear density field explains:
//   dρ_i/dt += δ h c0 Σ_j V_j [(ρ_i − ρ_j) − ½ (∇ρ^L_i + ∇ρ^L_j)·r_ij] (r_ij·∇_i W_ij) / (r² + 0.01 h²)
//   ∇ρ^L_i = Σ_j (ρ_j − ρ_i) V_j L_i ∇_i W_ij,   L_i = (−Σ_j V_j r_ij ⊗ ∇_i W_ij)⁻¹
// (the renormalised density gradient; L_i = I where the matrix is singular, e.g. a particle
// alone). In a column at rest the density is linear in depth and the bracket vanishes. Fluid
// pairs only; h the support radius (= 2 h_s). A pass more than molteni (the gradients, kept in
// the scratch field `densityGradient`).
//
//   densityDiffusion { type antuono; delta 0.1; }
#include "DensityDiffusion.hpp"
#include "KernelCorrection.hpp" // renormalised
#include "PairLoop.hpp"
#include "Plugin.hpp"

namespace {
using namespace spindrift;

// Σ_j V_j (ρ_j − ρ_i) ∇W_ij and −Σ_j V_j r_ij ⊗ ∇W_ij.
struct DensityGradientTerm {
    struct Sum {
        Vec3 gradient = Vec3::Zero();
        Mat3 moment = Mat3::Zero();
    };
    static constexpr bool usesGradient = true;
    using Particle = Scalar; // ρ_i
    const Scalar* rho;
    Scalar m;
    Particle particle(std::size_t i) const { return rho[i]; }
    void fluid(Scalar rhoi, const Pair& q, Sum& sum) const {
        const Scalar V = m / rho[q.j];
        sum.gradient += (V * (rho[q.j] - rhoi)) * q.gradW;
        sum.moment -= V * q.r * q.gradW.transpose();
    }
};

struct AntuonoTerm {
    using Sum = Scalar;
    static constexpr bool usesDampedGradient = true; // (r_ij·∇W_ij)/(r² + 0.01 h²) = r² q.dampedGradFactor
    struct Particle {
        Scalar rho;
        Vec3 gradient;
    };
    const Scalar* rho;
    const Scalar* invRho; // 1/ρ_j (DensityDiffusion::inverseDensity)
    const Vec3* gradient;
    Particle particle(std::size_t i) const { return {rho[i], gradient[i]}; }
    void fluid(const Particle& pi, const Pair& q, Sum& sum) const {
        const Scalar bracket = pi.rho - rho[q.j] - Scalar(0.5) * (pi.gradient + gradient[q.j]).dot(q.r);
        sum += bracket * invRho[q.j] * q.r2 * q.dampedGradFactor;
    }
};

class Antuono final : public DensityDiffusion {
public:
    explicit Antuono(const ModelContext& c) : delta_(c.dict.getOrDefault<double>("delta", 0.1)) {
        if (!(delta_ >= 0)) throw InputError(c.dict.locationOf("delta"), "delta must not be negative", "delta");
    }

    void initialise(Scene& s) override { dimension_ = s.physics.dimension; }

    void densityRate(const Scene& s, const ParticleSystem& fluid, std::vector<Scalar>& rate) const override {
        const Scalar m = fluid.particles.particleMass(), h = s.constants.supportRadius;
        const auto& x = fluid.particles.position();
        const Scalar* rho = fluid.particles.density().data();
        auto& gradient = gradient_;
        gradient.resize(x.size());
        const int d = dimension_;
        forEachPairSum(s, fluid, x, DensityGradientTerm{rho, m}, [&](std::size_t i, Scalar, const auto& sum) {
            gradient[i] = renormalised(sum.moment, sum.gradient, d);
        });
        const Scalar scale = delta_ * h * s.constants.soundSpeed * m;
        continuityDensityRate(s, fluid, rate, AntuonoTerm{rho, inverseDensity(fluid), gradient.data()}, scale);
    }

private:
    Scalar delta_;
    mutable std::vector<Vec3> gradient_; // the renormalised density gradient (scratch of a call)
    int dimension_ = 2;
};
} // namespace

SPINDRIFT_PLUGIN(DensityDiffusion, Antuono)
