// leapfrog — kick–drift–kick leapfrog (velocity form): v_{n+½} = v_n + ½Δt a_n,
// x_{n+1} = x_n + Δt v_{n+½}, a_{n+1} = a(x_{n+1}, v_{n+½}), v_{n+1} = v_{n+½} + ½Δt a_{n+1}.
// Second order for velocity-independent forces; one evaluation per step (a_{n+1} is reused as
// the next step's a_n).
#include "Integrator.hpp"
#include "Plugin.hpp"

namespace {
using namespace spindrift;

class Leapfrog final : public Integrator {
public:
    explicit Leapfrog(const ModelContext&) {}

    // After step 0 the accelerations at the current state were computed at the end of the
    // previous step (with the half-step velocities) and restored from the time directory.
    void restarted(SphSystem& s) override { haveAcceleration_ = s.step > 0; }

    void step(SphSystem& s, Scalar dt, const Evaluate& evaluate) override {
        if (!haveAcceleration_) evaluate();
        auto& x = s.fluid.position();
        auto& v = s.fluid.velocity();
        auto& a = s.fluid.acceleration();
        const Scalar half = Scalar(0.5) * dt;
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < x.size(); ++i) {
            v[i] += half * a[i];
            x[i] += dt * v[i];
        }
        evaluate();
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < x.size(); ++i) v[i] += half * a[i];
        haveAcceleration_ = true;
    }

private:
    bool haveAcceleration_ = false;
};
} // namespace

SPINDRIFT_PLUGIN(Integrator, Leapfrog)
