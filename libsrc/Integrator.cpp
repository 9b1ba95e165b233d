#include "Integrator.hpp"

namespace spindrift {

void advanceIntegratedFields(Scene& s, Scalar dt) {
    for (const IntegratedField& f : s.integratedFields) {
        auto& rate = *f.rate;
        f.computeRate(s, rate);
        auto& value = *f.value;
        forEachFluidParticle(s, [&](std::size_t i) { value[i] += dt * rate[i]; });
    }
}

} // namespace spindrift
