// libFuzzer target: a case's set-up semantics beyond the parser — constant/fluidProperties
// (readPhysicalParameters) and constant/geometry (the particle estimate, the sampling, the
// walls' motions), as the solver reads them before allocating anything. The input is the two
// files separated by a NUL byte. Any input must end in an InputError or a sampled geometry
// whose positions are finite and whose particle count the estimate (which guards memory) did
// not underestimate — never a crash, a leak, a hang or another exception.
#include "Case.hpp"
#include "FuzzSupport.hpp"
#include "Geometry.hpp"
#include "Motion.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

using namespace spindrift;
using fuzz::check;

namespace {
// at most this many particles sampled per input (the solver asks for -force far above that;
// the fuzzer stays fast)
constexpr double maxParticles = 2e4;

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fuzz::quietLog();
    const std::string text(reinterpret_cast<const char*>(data), size);
    const std::size_t split = text.find('\0');
    if (split == std::string::npos) return 0;
    try {
        const Dictionary fluid = Dictionary::fromString(text.substr(0, split), "constant/fluidProperties");
        const Dictionary geometry = Dictionary::fromString(text.substr(split + 1), "constant/geometry");
        const PhysicalParameters physics = readPhysicalParameters(fluid);
        const ParticleEstimate estimate =
            estimateParticleCount(geometry, physics.particleSpacing, physics.dimension);
        check(estimate.count >= 0 && !std::isnan(estimate.count));
        if (!(estimate.count <= maxParticles)) return 0;
        const SampledGeometry g = sampleGeometry(geometry, physics.particleSpacing, physics.dimension, physics.gravity);
        double sampled = double(g.fluidPositions.size());
        check(g.fluidVelocities.size() == g.fluidPositions.size() && g.fluidDepths.size() == g.fluidPositions.size());
        for (const Scalar depth : g.fluidDepths) check(depth >= 0 && std::isfinite(depth));
        for (const auto& x : g.fluidPositions) check(x.allFinite());
        for (const auto& v : g.fluidVelocities) check(v.allFinite());
        for (const auto& w : g.walls) {
            sampled += double(w.positions.size());
            for (const auto& x : w.positions) check(x.allFinite());
            if (w.motion) {
                // a motion read for a run from 0 to 1 is finite over it (Motion::read checks)
                const auto motion = Motion::read(*w.motion, physics.dimension, 0.0, 1.0);
                Vec3 lo, hi;
                motion->sweptRange(0.0, 1.0, w.min, w.max, lo, hi);
                check(lo.allFinite() && hi.allFinite() && motion->displacement(0.5).allFinite());
                (void)motion->describe();
            }
        }
        // the estimate may count a little more than is sampled (overlaps, walls' open faces),
        // never much less: it is what refuses a geometry that would not fit in memory
        check(sampled <= 2 * estimate.count + 1000);
    } catch (const InputError&) {
    }
    return 0;
}
