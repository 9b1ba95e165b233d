// surgeFront — position of the leading edge of the fluid: the largest (x_i − origin)·d over
// fluid particles i, d the unit `direction` (the dam-break "surge front" of Martin & Moyce
// 1952 and of every SPH dam-break validation since Monaghan 1994). Options restrict the
// particles that count: only those within `maxHeight` of the origin along "up" (−gravity),
// i.e. near the floor, and only those with at least `minNeighbours` fluid neighbours within
// the support radius (so isolated spray ahead of the front is ignored). The position is that
// of the particle centre (half a particle spacing behind the fluid's edge).
//
//   front
//   {
//       type            surgeFront;
//       direction       (1 0 0);
//       origin          (0 0 0);        // front measured from here
//       maxHeight       0.01;           // optional: particles below origin + maxHeight·up
//       minNeighbours   0;              // optional
//       writeControl    timeStep;  writeInterval 1;
//   }
//
// Output postProcessing/<name>/<startTime>/<name>.dat: Time, front, and the front particle's
// coordinates (m). A row is written at the start time too.
#include "FunctionObjectSupport.hpp"
#include "Plugin.hpp"

namespace {
using namespace spindrift;
using namespace spindrift::functionObjects;

class SurgeFront final : public SamplingFunctionObject {
public:
    explicit SurgeFront(const ModelContext& c)
        : SamplingFunctionObject(c) {
        direction_ = c.dict.getOrDefault<Vec3>("direction", Vec3(1, 0, 0));
        if (dim_ == 2) direction_[2] = 0;
        if (!(direction_.norm() > 0))
            throw InputError(c.dict.locationOf("direction"), "direction must not be zero", "direction");
        direction_.normalize();
        origin_ = c.dict.getOrDefault<Vec3>("origin", Vec3::Zero());
        if (c.dict.found("maxHeight")) {
            maxHeight_ = c.dict.get<double>("maxHeight");
            const Scalar g = c.physics.gravity.norm();
            if (!(g > 0))
                throw InputError(c.dict.locationOf("maxHeight"), "maxHeight needs gravity to tell 'up'", "maxHeight");
            up_ = -c.physics.gravity / g;
            useHeight_ = true;
        }
        minNeighbours_ = c.dict.getOrDefault<int>("minNeighbours", 0);
    }

    void start(const Scene& s, double startTime) override {
        std::vector<PostProcessingColumn> columns{{"front", "m"}, {"x", "m"}, {"y", "m"}};
        if (dim_ == 3) columns.push_back({"z", "m"});
        open(s, startTime, columns);
        sample(s, false);
    }

private:
    void sample(const Scene& s, bool listsValid) override {
        const ParticleSystem& fluid = sampled();
        const auto& x = fluid.particles.position();
        const QueryLists& q = s.listsOf(fluid);
        // neighbour counts are those of the step's last search (same particle order)
        const bool countNeighbours = minNeighbours_ > 0 && listsValid && q.hasOwn() && q.size() == fluid.ownedSize();
        double best = -std::numeric_limits<double>::infinity();
        long bestIndex = -1;
        for (std::size_t i = 0; i < fluid.ownedSize(); ++i) {
            const Vec3 r = x[i] - origin_;
            if (useHeight_ && r.dot(up_) > maxHeight_) continue;
            if (countNeighbours && int(q.own().count(i)) < minNeighbours_) continue;
            const double d = r.dot(direction_);
            if (d > best) {
                best = d;
                bestIndex = long(i);
            }
        }
        std::vector<double> row{bestIndex < 0 ? notANumber : best};
        for (int a = 0; a < dim_; ++a) row.push_back(bestIndex < 0 ? notANumber : double(x[bestIndex][a]));
        file_.writeRow(s.time, row);
    }

    Vec3 direction_, origin_, up_ = Vec3::Zero();
    double maxHeight_ = 0;
    bool useHeight_ = false;
    int minNeighbours_ = 0;
};
} // namespace

SPINDRIFT_PLUGIN(FunctionObject, SurgeFront)
