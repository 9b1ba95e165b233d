// symplecticEuler — semi-implicit Euler: v_{n+1} = v_n + Δt a(x_n, v_n), x_{n+1} = x_n + Δt v_{n+1}.
// First order, symplectic; the integrator PCISPH and PBF are formulated with.
#include "Integrator.hpp"
#include "Plugin.hpp"

namespace {
using namespace spindrift;

class SymplecticEuler final : public Integrator {
public:
    explicit SymplecticEuler(const ModelContext&) {}

    void step(SphSystem& s, Scalar dt, const Evaluate& evaluate) override {
        evaluate();
        auto& x = s.fluid.position();
        auto& v = s.fluid.velocity();
        const auto& a = s.fluid.acceleration();
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < x.size(); ++i) {
            v[i] += dt * a[i];
            x[i] += dt * v[i];
        }
    }
};
} // namespace

SPINDRIFT_PLUGIN(Integrator, SymplecticEuler)
