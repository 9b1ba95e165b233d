// artificial — Monaghan (1992) artificial viscosity (MODELS.md "Viscosity"):
// a_i = −Σ_j m_j Π_ij ∇_i W_ij,  Π_ij = −α c̄ μ_ij / ρ̄_ij for v_ij·r_ij < 0 (else 0),
// μ_ij = h v_ij·r_ij / (r² + 0.01 h²), with h the support radius, c̄ the sound speed.
// Walls act as particles at rest with the fluid particle's density (wallFactor scales them;
// 0 = free slip). Pairwise antisymmetric: momentum is conserved among fluid particles. ∇W_ij is
// read from the pressure model's cache of the step's pairs when it keeps one (dfsph).
//
//   viscosity { type artificial; alpha 0.05; soundSpeed 20; wallFactor 1; }
#include "Plugin.hpp"
#include "SphOperators.hpp"
#include "ViscosityModel.hpp"

namespace {
using namespace spindrift;

class Artificial final : public ViscosityModel {
public:
    explicit Artificial(const ModelContext& c)
        : alpha_(c.dict.getOrDefault<double>("alpha", 0.05)),
          soundSpeed_(c.dict.found("soundSpeed") ? c.dict.get<double>("soundSpeed") : 0.0),
          wallFactor_(c.dict.getOrDefault<double>("wallFactor", 1.0)) {
        if (alpha_ < 0) throw InputError(c.dict.locationOf("alpha"), "alpha must not be negative", "alpha");
        soundSpeedLocation_ = c.dict.locationOf("soundSpeed");
    }

    void initialise(SphSystem& s) override {
        if (soundSpeed_ <= 0) soundSpeed_ = s.soundSpeed;
        if (soundSpeed_ <= 0)
            throw InputError(soundSpeedLocation_, "artificial viscosity needs a sound speed: the pressure "
                                                  "model has none (incompressible), so give 'soundSpeed'", "soundSpeed");
    }

    void addAcceleration(SphSystem& s, Scalar) override {
        const auto& kt = s.kernel;
        const Scalar m = s.fluid.particleMass(), h = kt.supportRadius(), eps = Scalar(0.01) * h * h;
        const Scalar ac = alpha_ * soundSpeed_;
        const auto& x = s.fluid.position();
        const auto& v = s.fluid.velocity();
        const auto& rho = s.fluid.density();
        auto& a = s.fluid.acceleration();
        const auto& xb = s.boundary.position();
        const Scalar* psi = s.boundaryMass ? s.boundaryMass->data() : nullptr;
        const Scalar wall = wallFactor_;
        // −m Π_ij ∇W_ij = 2 m α c h · v_ij·r_ij / ((r² + ε)(ρ_i + ρ_j)) ∇W_ij: one division a pair
        const Scalar fluidScale = 2 * m * ac * h, wallScale = wall * ac * h;
        const auto& ff = s.search.fluidNeighbours();
        // ∇W_ij from the pressure model's cache of the step's pairs when it keeps one, else the table
        const Vec3* cached = s.fluidPairGradients ? s.fluidPairGradients->data() : nullptr;
        const auto pass = [&](auto gradient) {
            forEachParticleBalanced(s.search, [&](std::size_t i) {
                const Vec3 vi = v[i];
                const Scalar rhoi = rho[i];
                Vec3 acc = Vec3::Zero();
                std::uint32_t k = ff.offsets[i];
                forEachNeighbour(ff, x, x, i, [&](Index j, const Vec3& rij, Scalar r2) {
                    // approaching pairs only; min() instead of a branch (taken for about half
                    // the pairs, unpredictably)
                    const Scalar vr = std::min((vi - v[j]).dot(rij), Scalar(0));
                    acc += (vr / ((r2 + eps) * (rhoi + rho[j]))) * gradient(k++, rij, r2);
                });
                acc *= fluidScale;
                if (psi && wall != 0) {
                    Vec3 accWall = Vec3::Zero();
                    forEachNeighbour(s.search.boundaryNeighbours(), x, xb, i, [&](Index b, const Vec3& rib, Scalar r2) {
                        const Scalar vr = std::min(vi.dot(rib), Scalar(0));
                        accWall += (psi[b] * vr / (r2 + eps)) * kt.gradWSq(rib, r2);
                    });
                    acc += (wallScale / rhoi) * accWall;
                }
                a[i] += acc;
            });
        };
        if (cached) pass([&](std::uint32_t k, const Vec3&, Scalar) { return cached[k]; });
        else pass([&](std::uint32_t, const Vec3& rij, Scalar r2) { return kt.gradWSq(rij, r2); });
    }

private:
    Scalar alpha_, soundSpeed_, wallFactor_;
    SourceLocation soundSpeedLocation_;
};
} // namespace

SPINDRIFT_PLUGIN(ViscosityModel, Artificial)
