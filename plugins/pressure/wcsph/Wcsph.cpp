// wcsph — weakly compressible SPH (Monaghan 1994; Becker & Teschner 2007; MODELS.md
// "Pressure terms"): summation density with wall contributions, Tait equation of state, and
// the symmetric gradient a_i = −Σ_j m_j (p_i/ρ_i² + p_j/ρ_j²) ∇_i W_ij (momentum-conserving).
//
//   pressure { type wcsph; gamma 7; soundSpeed 20; clampNegativePressure yes; }
#include "PressureModel.hpp"
#include "Plugin.hpp"
#include "SphOperators.hpp"
#include "TaitEquationOfState.hpp"

namespace {
using namespace spindrift;

class Wcsph final : public PressureModel {
public:
    explicit Wcsph(const ModelContext& c) { eos_.read(c.dict, c.physics.rho0); }

    void initialise(SphSystem& s) override { eos_.initialise(s); }

    void computeDensity(SphSystem& s) override {
        auto& rho = s.fluid.density();
        auto& p = s.fluid.pressure();
        summationDensity(s, s.fluid.position(), rho);
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < rho.size(); ++i) p[i] = eos_.pressure(rho[i]);
    }

    void addPressureAcceleration(SphSystem& s, Scalar) override {
        addSymmetricPressureAcceleration(s, s.fluid.position(), s.fluid.pressure(), s.fluid.density(),
                                         s.fluid.acceleration(), WallMasses::ofBoundaryModel(s), pOverRho2_);
    }

    Scalar soundSpeed() const override { return eos_.soundSpeed; }

private:
    TaitEquationOfState eos_;
    std::vector<Scalar> pOverRho2_; // scratch of the force pass
};
} // namespace

SPINDRIFT_PLUGIN(PressureModel, Wcsph)
