// wcsph — weakly compressible SPH (Monaghan 1994; Becker & Teschner 2007;
// docs/MODELS.md §wcsph): summation or continuity density (§continuity) with wall contributions, Tait equation of state, and
// the symmetric gradient a_i = −Σ_j m_j (p_i/ρ_i² + p_j/ρ_j²) ∇_i W_ij (momentum-conserving), or
// with `gradientCorrection yes` its kernel-corrected form (KernelCorrection.hpp: exact for a
// linear pressure inside the fluid; docs/MODELS.md §gradientCorrection).
//
//   pressure { type wcsph; gamma 7; soundSpeed 20; clampNegativePressure yes; gradientCorrection no; }
#include "PressureModel.hpp"
#include "Plugin.hpp"
#include "KernelCorrection.hpp"
#include "PairLoop.hpp"
#include "TaitEquationOfState.hpp"

namespace {
using namespace spindrift;

class Wcsph final : public PressureModel {
public:
    explicit Wcsph(const ModelContext& c) : corrected_(c.dict.getOrDefault<bool>("gradientCorrection", false)) {
        eos_.read(c.dict, c.physics.rho0);
    }

    Scalar soundSpeed(const SceneConstants& c, const PhysicalParameters& physics) const override {
        return eos_.resolveSoundSpeed(c, physics);
    }
    Scalar eosExponent() const override { return eos_.gamma; }
    void initialise(Scene& s) override { eos_.initialise(s); }
    bool integratesDensity() const override { return eos_.continuity; }

    void computeDensity(Scene& s, ParticleSystem& fluid, const Step&) override { eos_.densityAndPressure(s, fluid); }
    void addPressureAcceleration(Scene& s, ParticleSystem& fluid, const Step&) override {
        if (!corrected_) {
            addSymmetricPressureAcceleration(s, fluid, pOverRho2_);
            return;
        }
        pressureOverDensitySquared(fluid, pOverRho2_);
        kernelCorrectionMatrices(s, fluid, fluid.particles.position(), correction_);
        addCorrectedSymmetricPressureAcceleration(s, fluid, pOverRho2_, correction_);
    }
    void addReactions(const Scene& s, const ParticleSystem& fluid, const Step&, Reactions& r) const override {
        if (corrected_) addCorrectedSymmetricPressureReactions(s, fluid, pOverRho2_, correction_, r);
        else addSymmetricPressureReactions(s, fluid, fluid.particles.position(), pOverRho2_.data(), r);
    }

private:
    TaitEquationOfState eos_;
    bool corrected_; // gradientCorrection
    std::vector<Scalar> pOverRho2_; // scratch of the force pass
    std::vector<Mat3> correction_;  // L_i of the corrected gradient (scratch of the force pass)
};
} // namespace

SPINDRIFT_PLUGIN(PressureModel, Wcsph)
