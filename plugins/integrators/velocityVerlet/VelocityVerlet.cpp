// velocityVerlet — velocity Verlet in the form usual for SPH, where forces depend on velocity
// (viscosity) as well as position:
//   x_{n+1} = x_n + Δt v_n + ½Δt² a_n
//   v*      = v_n + Δt a_n                       (predicted velocity for the force evaluation)
//   a_{n+1} = a(x_{n+1}, v*)
//   v_{n+1} = v_n + ½Δt (a_n + a_{n+1})
// One evaluation per step (a_{n+1} is the next step's a_n). Second order for position- and
// velocity-dependent forces alike (v* is first-order accurate, which a ½Δt factor makes a
// third-order local error); identical to leapfrog when forces depend on position only.
#include "Integrator.hpp"
#include "Plugin.hpp"

namespace {
using namespace spindrift;

class VelocityVerlet final : public Integrator {
public:
    explicit VelocityVerlet(const ModelContext&) {}

    // After step 0 the accelerations at the current state were computed at the end of the
    // previous step and restored from the time directory with the other restart fields.
    void restarted(SphSystem& s) override { haveAcceleration_ = s.step > 0; }

    void step(SphSystem& s, Scalar dt, const Evaluate& evaluate) override {
        if (!haveAcceleration_) evaluate();
        auto& x = s.fluid.position();
        auto& v = s.fluid.velocity();
        auto& a = s.fluid.acceleration();
        const std::size_t n = x.size();
        halfKick_.resize(n); // v_n + ½Δt a_n, scratch within the step
        const Scalar half = Scalar(0.5) * dt;
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < n; ++i) {
            x[i] += dt * (v[i] + half * a[i]);
            halfKick_[i] = v[i] + half * a[i];
            v[i] += dt * a[i];
        }
        evaluate();
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < n; ++i) v[i] = halfKick_[i] + half * a[i];
        haveAcceleration_ = true;
    }

private:
    bool haveAcceleration_ = false;
    std::vector<Vec3> halfKick_;
};
} // namespace

SPINDRIFT_PLUGIN(Integrator, VelocityVerlet)
