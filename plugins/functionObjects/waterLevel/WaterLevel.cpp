// waterLevel — free-surface height at gauge positions, as DualSPHysics' GaugeSwl: along the
// vertical line through each gauge (up = −gravity) the mass-based kernel sum
//     φ(x) = Σ_j (m/ρ0) W(x − x_j)      (≈ 1 inside the fluid, ½ at a free surface)
// is scanned from above the highest fluid particle downwards; the level is the highest point
// where φ reaches `threshold` (default ½, the continuum value at a flat surface), refined by
// bisection to 1/64 of the particle spacing. A dry gauge reports the gauge point's own height.
// Levels are coordinates along "up" (the y coordinate for gravity (0 −g 0)).
//
//   gauges
//   {
//       type            waterLevel;
//       gaugeLocations  ((0.1 0 0) (0.3 0 0));   // base points of the vertical lines
//       threshold       0.5;
//       writeControl    timeStep;  writeInterval 10;
//   }
//
// Output postProcessing/<name>/<startTime>/<name>.dat: one column "level(x,y)" per gauge (m); a
// row is written at the start time too.
#include "FunctionObjectSupport.hpp"
#include "Plugin.hpp"

namespace {
using namespace spindrift;
using namespace spindrift::functionObjects;

class WaterLevel final : public SamplingFunctionObject {
public:
    explicit WaterLevel(const ModelContext& c)
        : SamplingFunctionObject(c), rho0_(c.physics.rho0), dx_(c.physics.particleSpacing) {
        gauges_ = c.dict.get<std::vector<Vec3>>("gaugeLocations");
        if (gauges_.empty())
            throw InputError(c.dict.locationOf("gaugeLocations"), "'gaugeLocations' lists no point", "gaugeLocations");
        if (dim_ == 2)
            for (auto& p : gauges_) p[2] = 0;
        threshold_ = c.dict.getOrDefault<double>("threshold", 0.5);
        if (!(threshold_ > 0 && threshold_ < 1))
            throw InputError(c.dict.locationOf("threshold"), "threshold must lie between 0 and 1", "threshold");
        const Scalar g = c.physics.gravity.norm();
        if (!(g > 0))
            throw InputError(c.dict.where(), "waterLevel needs gravity (constant/fluidProperties) to tell 'up'");
        up_ = -c.physics.gravity / g;
    }

    void start(const Scene& s, double startTime) override {
        std::vector<PostProcessingColumn> columns;
        for (const auto& p : gauges_) columns.push_back({columnLabel("level", p, dim_), "m"});
        open(s, startTime, columns);
        sample(s, false);
    }

private:
    Scalar phi(const Scene& s, const Vec3& p) const {
        Scalar sum = 0;
        forEachSampledWithin(s, p, [&](Index, Scalar r) { sum += s.kernel.W(r); });
        return sum * sampled().particles.particleMass() / rho0_;
    }

    void sample(const Scene& s, bool) override {
        const auto& x = sampled().particles.position();
        std::vector<double> row;
        for (const auto& base : gauges_) {
            Scalar top = 0;
            for (const auto& xi : x) top = std::max(top, (xi - base).dot(up_));
            top += s.constants.supportRadius;
            const Scalar step = Scalar(0.5) * dx_;
            Scalar above = top, level = -1;
            for (Scalar z = top; z >= 0; z -= step) {
                if (phi(s, base + z * up_) >= threshold_) {
                    // bisect between z (wet) and above (dry)
                    Scalar wet = z, dry = above;
                    while (dry - wet > dx_ / 64) {
                        const Scalar mid = Scalar(0.5) * (wet + dry);
                        (phi(s, base + mid * up_) >= threshold_ ? wet : dry) = mid;
                    }
                    level = Scalar(0.5) * (wet + dry);
                    break;
                }
                above = z;
            }
            row.push_back(double(base.dot(up_) + std::max(level, Scalar(0))));
        }
        file_.writeRow(s.time, row);
    }

    Scalar rho0_, dx_, threshold_ = 0.5;
    Vec3 up_;
    std::vector<Vec3> gauges_;
};
} // namespace

SPINDRIFT_PLUGIN(FunctionObject, WaterLevel)
