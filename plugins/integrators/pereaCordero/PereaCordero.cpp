// pereaCordero — the explicit multi-step Taylor integrator of Perea & Cordero (seed 000,
// eqs. 26–27; docs/MODELS.md §pereaCordero-integrator):
//   u_{n+1} = u_n + Δt v_n + ½Δt² a_n + β2 Δt²/6 · D_n
//   v_{n+1} = v_n + Δt a_n + β1 Δt/2 · D_n
//   D_n = c0 a_n + c1 a_{n−1} + c2 a_{n−2}       (`history (c0 c1 c2);`)
// As extracted the paper prints D_n = 2a_n − 2a_{n−1} + a_{n−2}, which equals a_n for a
// constant acceleration: a body in free fall gains speed (1 + β1/2) times too fast, so that
// combination (`history (2 -2 1);`) is inconsistent. The default (1.5 −2 0.5) is the
// backward-difference estimate of Δt·da/dt (zero for constant a): with β1 = β2 = 1 the scheme is
// a third-order Taylor step of second-order global accuracy; the paper's β1 = 0.7586,
// β2 = 1.101 leave a first-order velocity error (β1 − 1)Δt²/2 · da/dt per step.
// Eq. 28 is not an update (its units are wrong): a_{n+1} always comes from the forces at the
// new state. Until a particle has two steps of history, a_{n−1} = a_{n−2} = a_n. The history
// combination assumes equal steps (with adjustTimeStep, Δt changes slowly and D_n stays a
// consistent estimate of Δt·da/dt to first order).
// History lives in fluid fields (re-sorted with the particles, written for restarts):
// accelerationOld1 = a_{n−1}, accelerationOld2 = a_{n−2}, historyLength (0, 1, 2; new
// particles start at 0). One force evaluation per step.
//
//   integrator { type pereaCordero; beta1 0.7586; beta2 1.101; history (1.5 -2 0.5); }
#include "Integrator.hpp"
#include "Log.hpp"
#include "Plugin.hpp"

#include <cmath>
#include <sstream>

namespace {
using namespace spindrift;

class PereaCordero final : public CarriedAccelerationIntegrator {
public:
    explicit PereaCordero(const ModelContext& c)
        : beta1_(c.dict.getOrDefault<double>("beta1", 0.7586)), beta2_(c.dict.getOrDefault<double>("beta2", 1.101)) {
        const auto h = c.dict.getOrDefault<std::vector<double>>("history", {1.5, -2.0, 0.5});
        if (h.size() != 3)
            throw InputError(c.dict.locationOf("history"),
                             "history needs three coefficients (c0 c1 c2) of a_n, a_{n-1}, a_{n-2}", "history");
        for (int k = 0; k < 3; ++k) c_[k] = h[k];
        const double sum = h[0] + h[1] + h[2];
        if (std::abs(sum) > 1e-12) {
            std::ostringstream m;
            m << "integrator pereaCordero: history (" << h[0] << " " << h[1] << " " << h[2]
              << ") does not vanish for a constant acceleration (sum " << sum
              << "): the scheme is inconsistent (free fall gains speed " << 1 + beta1_ * sum / 2 << " times too fast)";
            log::warning(m.str());
        }
    }

    // second order with β1 = 1 (β2 enters the position's third-order term only), first with the
    // paper's β1, none with a history that does not vanish for a constant acceleration
    int order() const override {
        if (std::abs(c_[0] + c_[1] + c_[2]) > 1e-12) return 0;
        return beta1_ == 1 ? 2 : 1;
    }

    void initialise(Scene& s) override {
        // allocated only when this integrator is chosen; needed for an exact restart
        for (ParticleSystem* fluid : s.ofRole(SystemRole::fluid)) {
            fluid->particles.addVector("accelerationOld1", {false, true});
            fluid->particles.addVector("accelerationOld2", {false, true});
            fluid->particles.addScalar("historyLength", {false, true});
            fluid->particles.addVector("pereaCorderoMidVelocity", {false, false, true});
        }
    }

    void step(Scene& s, const StepServices& core, Scalar dt, const Evaluate& evaluate) override {
        startStep(s, dt, evaluate);
        for (ParticleSystem* fluid : s.ofRole(SystemRole::fluid)) advance(s, core, *fluid, dt);
        evaluateAtEnd(s, dt, evaluate);
    }

private:
    void advance(Scene& s, const StepServices& core, ParticleSystem& fluid, Scalar dt) const {
        auto& x = fluid.particles.position();
        auto& v = fluid.particles.velocity();
        const auto& a = fluid.particles.acceleration();
        auto& a1 = *fluid.particles.findVector("accelerationOld1");
        auto& a2 = *fluid.particles.findVector("accelerationOld2");
        auto& level = *fluid.particles.findScalar("historyLength");
        const Scalar c0 = c_[0], c1 = c_[1], c2 = c_[2];
        const Scalar kx = beta2_ * dt * dt / 6, kv = beta1_ * dt / 2, half = Scalar(0.5) * dt * dt;
        // an integrated density (continuity) with the mid-step velocities at x_n
        if (core.integratesDensity(fluid)) {
            auto& mid = *fluid.particles.findVector("pereaCorderoMidVelocity"); // v_n meanwhile
            forEachParticleOf(fluid, [&](std::size_t i) {
                mid[i] = v[i];
                v[i] += Scalar(0.5) * dt * a[i];
            });
            core.advanceDensity(s, fluid, dt);
            forEachParticleOf(fluid, [&](std::size_t i) { v[i] = mid[i]; });
        }
        // x_{n+1} = x_n + Δt (v_n + δv) (the core's drift), then the Taylor terms
        core.drift(s, fluid, dt, v, x);
        forEachParticleOf(fluid, [&](std::size_t i) {
            const bool full = level[i] >= 2;
            const Vec3 am1 = full ? a1[i] : a[i], am2 = full ? a2[i] : a[i];
            const Vec3 d = c0 * a[i] + c1 * am1 + c2 * am2;
            x[i] += half * a[i] + kx * d;
            v[i] += dt * a[i] + kv * d;
            a2[i] = level[i] >= 1 ? a1[i] : a[i];
            a1[i] = a[i];
            level[i] = std::min<Scalar>(level[i] + 1, 2);
        });
        core.wrap(s, fluid, x);
    }

    Scalar beta1_, beta2_;
    Scalar c_[3];
};
} // namespace

SPINDRIFT_PLUGIN(Integrator, PereaCordero)
