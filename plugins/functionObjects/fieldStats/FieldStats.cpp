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
        open(startTime, columns);
        sample(s, false);
    }

private:
    void sample(const Scene& s, bool listsValid) override {
        const auto& x = s.fluid.position();
        const auto& v = s.fluid.velocity();
        const auto& rho = s.fluid.density();
        const std::size_t n = x.size();
        const double rho0 = s.physics.rho0, m = s.fluid.particleMass();
        std::vector<double> row{double(n)};
        if (n == 0) {
            row.resize(5 + dim_ + 2 + 2 * dim_, notANumber);
            row[0] = 0;
            file_.writeRow(s.time, row);
            return;
        }
        const double percent = 100 / rho0; // (ρ − ρ0)/ρ0 in %
        double errMin = (rho[0] - rho0) * percent, errMax = errMin;
#pragma omp parallel for schedule(static) reduction(min : errMin) reduction(max : errMax)
        for (std::size_t i = 1; i < n; ++i) {
            const double e = (rho[i] - rho0) * percent;
            errMax = std::max(errMax, e);
            errMin = std::min(errMin, e);
        }
        const double errAvg = deterministicSum(n, [&](std::size_t i) { return (rho[i] - rho0) * percent; }) / double(n);
        const double ke = 0.5 * m * deterministicSum(n, [&](std::size_t i) { return double(v[i].squaredNorm()); });
        row.insert(row.end(), {errMin, errMax, errAvg, ke});
        for (int a = 0; a < dim_; ++a)
            row.push_back(m * deterministicSum(n, [&](std::size_t i) { return double(v[i][a]); }));
        row.push_back(std::sqrt(parallelMax(n, [&](std::size_t i) { return double(v[i].squaredNorm()); })));
        row.push_back(minPairDistance(s, listsValid));
        Vec3 lo = x[0], hi = x[0];
        for (const auto& p : x) {
            lo = lo.cwiseMin(p);
            hi = hi.cwiseMax(p);
        }
        for (int a = 0; a < dim_; ++a) {
            row.push_back(lo[a]);
            row.push_back(hi[a]);
        }
        file_.writeRow(s.time, row);
    }

    // Over the step's fluid neighbour list when it matches the particles (after a step),
    // otherwise over a grid built here (start time).
    double minPairDistance(const Scene& s, bool listsValid) {
        const auto& x = s.fluid.position();
        const std::size_t n = x.size();
        const auto& list = s.search.fluidNeighbours();
        double r2min = std::numeric_limits<double>::infinity();
        if (listsValid && list.size() == n) {
#pragma omp parallel for schedule(static) reduction(min : r2min)
            for (std::size_t i = 0; i < n; ++i)
                forEachNeighbour(list, x, x, i, [&](Index, const Vec3&, Scalar r2) { r2min = std::min(r2min, double(r2)); });
        } else {
            grid_.build(s);
            for (std::size_t i = 0; i < n; ++i)
                grid_.forEachWithin(s, x[i], [&](Index j, Scalar r) {
                    if (j != i) r2min = std::min(r2min, double(r) * double(r));
                });
        }
        return std::isfinite(r2min) ? std::sqrt(r2min) : notANumber;
    }

    SampleGrid grid_;
};
} // namespace

SPINDRIFT_PLUGIN(FunctionObject, FieldStats)
