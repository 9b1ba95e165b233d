// Tait equation of state (Becker & Teschner 2007; docs/MODELS.md §tait), shared by
// the weakly compressible pressure plugins: p = B((ρ/ρ0)^γ − 1), B = c0² ρ0 / γ.
//
// Dictionary keywords (read by read()): gamma (7), soundSpeed c0 [m/s] (default
// 10·sqrt(2|g|H) from the initial fluid height H along gravity, i.e. ~1 % density variation
// for a free fall from H), clampNegativePressure (yes: p = max(p, 0), for free surfaces),
// density (summation: ρ_i = Σ_j m W_ij + Σ_b M_b W_ib from the positions | continuity: ρ is
// integrated in time from dρ_i/dt = Σ_j m v_ij·∇W_ij + Σ_b M_b v_ib·∇W_ib, Monaghan 1992 — no
// deficit at a free surface, the density a density-diffusion term (δ-SPH) acts on, and the one
// a hydrostatic start sets).
// The sound speed is resolved once at set-up (resolveSoundSpeed, through the pressure model's
// soundSpeed()) and read back from Scene::constants in initialise(). With continuity density the
// core advances the density (PressureModel::integratesDensity, StepServices::advanceDensity).
#pragma once

#include "Dictionary.hpp"
#include "Log.hpp"
#include "PairLoop.hpp"

#include <cmath>
#include <sstream>

namespace spindrift {

struct TaitEquationOfState {
    Scalar gamma = 7;
    Scalar soundSpeed = 0; // 0 until resolved
    bool clampNegative = true;
    bool continuity = false; // density by the continuity equation (integrated), not by summation
    Scalar rho0 = 1000;
    Scalar B = 0;
    int integerGamma = 0; // γ when it is a whole number (7): (ρ/ρ0)^γ by multiplication, not pow

    void read(const Dictionary& d, Scalar restDensity) {
        rho0 = restDensity;
        gamma = d.getOrDefault<double>("gamma", 7.0);
        if (!(gamma > 0)) throw InputError(d.locationOf("gamma"), "gamma must be positive", "gamma");
        soundSpeed = d.found("soundSpeed") ? d.get<double>("soundSpeed") : 0.0;
        if (d.found("soundSpeed") && !(soundSpeed > 0))
            throw InputError(d.locationOf("soundSpeed"), "soundSpeed must be positive", "soundSpeed");
        clampNegative = d.getOrDefault<bool>("clampNegativePressure", true);
        continuity = d.getWordOrDefault("density", {"summation", "continuity"}, "summation") == "continuity";
        integerGamma = gamma == std::round(gamma) && gamma <= 16 ? int(gamma) : 0;
        B = soundSpeed * soundSpeed * rho0 / gamma;
    }

    // The sound speed: the dictionary's, else 10 sqrt(2 |g| H) from the initial fluid height H
    // (SceneConstants::fluidHeight), else 10 m/s without gravity. Called once at set-up.
    Scalar resolveSoundSpeed(const SceneConstants& c, const PhysicalParameters& physics) const {
        if (soundSpeed > 0) return soundSpeed;
        const Scalar gNorm = physics.gravity.norm(), height = c.fluidHeight;
        const Scalar c0 = height > 0 && gNorm > 0 ? 10 * std::sqrt(2 * gNorm * height) : Scalar(10);
        std::ostringstream m;
        m << "    default: soundSpeed " << c0 << " m/s (10 sqrt(2 g H), H = " << height << " m)";
        log::info(m.str());
        return c0;
    }

    // Takes the sound speed the core resolved (Scene::constants), or resolves it the same way
    // where no core did (a model made by hand, as in the unit tests). With continuity density the
    // density is a field the core advances with its rate: its start is the one set-up gave (ρ0,
    // or a hydrostatic start's).
    void initialise(Scene& s) {
        soundSpeed = s.constants.soundSpeed > 0 ? s.constants.soundSpeed : resolveSoundSpeed(s.constants, s.physics);
        B = soundSpeed * soundSpeed * rho0 / gamma;
    }

    // The weakly compressible density and pressure: summation density (boundaries included), or
    // the integrated density as it is (continuity), then p_i = p(ρ_i) for every particle.
    void densityAndPressure(Scene& s, ParticleSystem& fluid) const {
        auto& rho = fluid.particles.density();
        auto& p = fluid.particles.pressure();
        if (!continuity) summationDensity(s, fluid, fluid.particles.position(), rho);
        forEachIndex(rho.size(), [&](std::size_t i) { p[i] = pressure(rho[i]); });
    }

    Scalar pressure(Scalar rho) const {
        const Scalar x = rho / rho0;
        const Scalar p = B * ((integerGamma ? wholePower(x, integerGamma) : std::pow(x, gamma)) - 1);
        return clampNegative && p < 0 ? Scalar(0) : p;
    }

    // x^n by squaring (x^7: 4 multiplications instead of a call to pow)
    static Scalar wholePower(Scalar x, int n) {
        Scalar result = 1;
        for (; n > 0; n >>= 1, x *= x)
            if (n & 1) result *= x;
        return result;
    }
};

} // namespace spindrift
