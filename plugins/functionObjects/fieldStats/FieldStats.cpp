// fieldStats — global measures of the fluid state for validation and stability checks:
//   nParticles                      number of fluid particles
//   rhoErrMin rhoErrMax rhoErrAvg   the density error (ρ_i − ρ0)/ρ0 in %, signed (> 0
//                                   compressed): min, max, average over the particles — the
//                                   log's "rhoErr min/max/avg", one definition (a free surface
//                                   shows as a negative minimum with summation density)
//   kineticEnergy                   Σ ½ m |v_i|²  (J; J/m per unit depth in 2D)
//   momentumX momentumY [momentumZ] Σ m v_i  (kg m/s; kg/s per unit depth in 2D)
//   maxSpeed                        max |v_i|
//   minPairDistance                 min |x_i − x_j| over fluid pairs closer than the support
//                                   radius (the particle-clustering measure; nan if none)
//   xMin xMax yMin yMax [zMin zMax] bounding box of the fluid particles
// Sums are deterministic (fixed-block reductions), whatever the thread count.
//
//   stats { type fieldStats; writeControl timeStep; writeInterval 1; }
//
// Output postProcessing/<name>/<startTime>/<name>.dat (units in the header's second line); a row
// is written at the start time too.
#include "FunctionObjectSupport.hpp"
#include "Plugin.hpp"

namespace {
using namespace spindrift;
using namespace spindrift::functionObjects;

class FieldStats final : public SamplingFunctionObject {
public:
    explicit FieldStats(const ModelContext& c) : SamplingFunctionObject(c) {}

    void start(const Scene& s, double startTime) override {
        const bool perDepth = dim_ == 2; // a 2D case's mass is per metre of depth
        std::vector<PostProcessingColumn> columns{{"nParticles", "-"},
                                                  {"rhoErrMin", "%"},
                                                  {"rhoErrMax", "%"},
                                                  {"rhoErrAvg", "%"},
                                                  {"kineticEnergy", perDepth ? "J/m" : "J"}};
        for (int a = 0; a < dim_; ++a) columns.push_back({std::string("momentum") + "XYZ"[a], perDepth ? "kg/s" : "kg*m/s"});
        columns.push_back({"maxSpeed", "m/s"});
        columns.push_back({"minPairDistance", "m"});
        for (int a = 0; a < dim_; ++a) {
            columns.push_back({std::string(1, "xyz"[a]) + "Min", "m"});
            columns.push_back({std::string(1, "xyz"[a]) + "Max", "m"});
        }
        open(s, startTime, columns);
        sample(s, false);
    }

private:
    void sample(const Scene& s, bool listsValid) override {
        const ParticleSystem& fluid = sampled();
        const auto& x = fluid.particles.position();
        const auto& v = fluid.particles.velocity();
        const auto& rho = fluid.particles.density();
        const std::size_t n = fluid.ownedSize();
        const double rho0 = fluid.rho0 > 0 ? double(fluid.rho0) : s.constants.rho0, m = fluid.particles.particleMass();
        std::vector<double> row{double(n)};
        if (n == 0) {
            row.resize(5 + dim_ + 2 + 2 * dim_, notANumber);
            row[0] = 0;
            file_.writeRow(s.time, row);
            return;
        }
        const double percent = 100 / rho0; // (ρ − ρ0)/ρ0 in %
        const double errMin = parallelMin(n, [&](std::size_t i) { return (rho[i] - rho0) * percent; });
        const double errMax = -parallelMin(n, [&](std::size_t i) { return -(rho[i] - rho0) * percent; });
        const double errAvg = deterministicSum(n, [&](std::size_t i) { return (rho[i] - rho0) * percent; }) / double(n);
        const double ke = 0.5 * m * deterministicSum(n, [&](std::size_t i) { return double(v[i].squaredNorm()); });
        row.insert(row.end(), {errMin, errMax, errAvg, ke});
        for (int a = 0; a < dim_; ++a)
            row.push_back(m * deterministicSum(n, [&](std::size_t i) { return double(v[i][a]); }));
        row.push_back(std::sqrt(parallelMax(n, [&](std::size_t i) { return double(v[i].squaredNorm()); })));
        row.push_back(minPairDistance(s, listsValid));
        Vec3 lo = x[0], hi = x[0];
        for (std::size_t i = 0; i < n; ++i) {
            lo = lo.cwiseMin(x[i]);
            hi = hi.cwiseMax(x[i]);
        }
        for (int a = 0; a < dim_; ++a) {
            row.push_back(lo[a]);
            row.push_back(hi[a]);
        }
        file_.writeRow(s.time, row);
    }

    // Over the step's own neighbour list of the system when it matches the particles (after a
    // step), otherwise over the search's point query at the current positions (start time).
    double minPairDistance(const Scene& s, bool listsValid) const {
        const ParticleSystem& fluid = sampled();
        const auto& x = fluid.particles.position();
        const std::size_t n = fluid.ownedSize();
        const QueryLists& q = s.listsOf(fluid);
        double r2min = std::numeric_limits<double>::infinity();
        if (listsValid && q.hasOwn() && q.size() == n) {
            const NeighbourList& list = q.own();
            r2min = parallelMin(n, [&](std::size_t i) {
                double m = std::numeric_limits<double>::infinity();
                forEachNeighbour(list, x, x, i, [&](Index, const Vec3&, Scalar r2) { m = std::min(m, double(r2)); });
                return m;
            });
        } else {
            for (std::size_t i = 0; i < n; ++i)
                forEachSampledWithin(s, x[i], [&](Index j, Scalar r) {
                    if (j != i) r2min = std::min(r2min, double(r) * double(r));
                });
        }
        return std::isfinite(r2min) ? std::sqrt(r2min) : notANumber;
    }
};
} // namespace

SPINDRIFT_PLUGIN(FunctionObject, FieldStats)
