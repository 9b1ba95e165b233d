// wcsph — weakly compressible SPH (Monaghan 1994; Becker & Teschner 2007;
// docs/MODELS.md §wcsph): summation or continuity density (§continuity) with wall contributions, Tait equation of state, and
// the symmetric gradient a_i = −Σ_j m_j (p_i/ρ_i² + p_j/ρ_j²) ∇_i W_ij (momentum-conserving).
//
//   pressure { type wcsph; gamma 7; soundSpeed 20; clampNegativePressure yes; }
#include "PressureModel.hpp"
#include "Plugin.hpp"
#include "PairLoop.hpp"
#include "TaitEquationOfState.hpp"

namespace {
using namespace spindrift;

class Wcsph final : public PressureModel {
public:
    explicit Wcsph(const ModelContext& c) { eos_.read(c.dict, c.physics.rho0); }

    Scalar soundSpeed(const SceneConstants& c, const PhysicalParameters& physics) const override {
        return eos_.resolveSoundSpeed(c, physics);
    }
    Scalar eosExponent() const override { return eos_.gamma; }
    void initialise(Scene& s) override { eos_.initialise(s); }
    bool integratesDensity() const override { return eos_.continuity; }

    void computeDensity(Scene& s, ParticleSystem& fluid, const Step&) override { eos_.densityAndPressure(s, fluid); }
    void addPressureAcceleration(Scene& s, ParticleSystem& fluid, const Step&) override {
        addSymmetricPressureAcceleration(s, fluid, pOverRho2_);
    }
    void addReactions(const Scene& s, const ParticleSystem& fluid, const Step&, Reactions& r) const override {
        addSymmetricPressureReactions(s, fluid, fluid.particles.position(), pOverRho2_.data(), r);
    }

private:
    TaitEquationOfState eos_;
    std::vector<Scalar> pOverRho2_; // scratch of the force pass
};
} // namespace

SPINDRIFT_PLUGIN(PressureModel, Wcsph)
