// probes — fluid fields at fixed points by SPH interpolation with Shepard normalisation
// (Shepard 1968; as DualSPHysics' MeasureTool and OpenFOAM's probes):
//     f(x) = Σ_j f_j V_j W(x − x_j) / Σ_j V_j W(x − x_j),   V_j = m/ρ_j,
// over fluid particles only. The normalisation makes a probe close to a wall or a free surface
// (truncated support) unbiased for a constant field; for wall pressure place the probe about
// 1.5 h inside the fluid from the wall, as DualSPHysics does, and compare with the value
// expected there. A probe with no fluid particle within the support radius writes nan.
// A location farther than the support radius from every particle of the case at the start
// (fluid and walls: outside the case's bounding box grown by h) is most likely a typo or a
// length in other units: it is warned about once at set-up, naming the point, the box and the
// probeLocations line (as OpenFOAM's probes warn of a location in no cell), and kept, its
// columns holding nan until fluid comes within h of it (a splash above an open container).
//
//   probes
//   {
//       type            probes;
//       fields          (pressure velocity density);   // or any scalar/vector fluid field
//       probeLocations  ((0.1 0.045 0) (0.1 0.15 0));
//       writeControl    timeStep;                      // timeStep | runTime | writeTime
//       writeInterval   10;
//   }
//
// Output postProcessing/<name>/<startTime>/<name>.dat (units in the header's second line: Pa,
// m/s, kg/m^3, ...; "?" for a model's internal field): one row per sample, columns field-major
// ("p(0.1,0.045)", ..., "Ux(0.1,0.045)", "Uy(...)", ..., "rho(...)"); a row is written at the
// start time too.
#include "FunctionObjectSupport.hpp"
#include "Log.hpp"
#include "Plugin.hpp"

namespace {
using namespace spindrift;
using namespace spindrift::functionObjects;

class Probes final : public SamplingFunctionObject {
public:
    explicit Probes(const ModelContext& c)
        : SamplingFunctionObject(c) {
        fieldNames_ = c.dict.getOrDefault<std::vector<std::string>>("fields", {"pressure", "velocity", "density"});
        fieldsWhere_ = c.dict.locationOf("fields");
        if (fieldNames_.empty()) throw InputError(fieldsWhere_, "'fields' lists no field", "fields");
        locations_ = c.dict.get<std::vector<Vec3>>("probeLocations");
        locationsWhere_ = c.dict.locationOf("probeLocations");
        if (locations_.empty())
            throw InputError(locationsWhere_, "'probeLocations' lists no point", "probeLocations");
        if (dim_ == 2)
            for (auto& p : locations_) p[2] = 0;
    }

    void start(const Scene& s, double startTime) override {
        fields_.clear();
        const ParticleSet& set = select(s).particles;
        std::vector<PostProcessingColumn> columns;
        for (const auto& f : fieldNames_) {
            Field field;
            field.name = f;
            field.unit = unitOf(f);
            if (f == "pressure" || f == "density" || set.findScalar(f)) {
                field.vector = false;
                field.label = f == "pressure" ? "p" : f == "density" ? "rho" : f;
            } else if (f == "velocity" || set.findVector(f)) {
                field.vector = true;
                field.label = f == "velocity" ? "U" : f + "_";
            } else {
                std::string known = "pressure velocity density";
                for (const auto& sf : set.scalarFields()) known += " " + sf->name;
                for (const auto& vf : set.vectorFields()) known += " " + vf->name;
                throw InputError(fieldsWhere_, "probes '" + name_ + "': unknown field '" + f + "' of " + set.name() +
                                                   "; its fields: (" + known + ")", "fields");
            }
            fields_.push_back(field);
        }
        for (const auto& f : fields_)
            for (const auto& p : locations_) {
                if (!f.vector) columns.push_back({columnLabel(f.label, p, dim_), f.unit});
                else
                    for (int a = 0; a < dim_; ++a) columns.push_back({columnLabel(f.label + "xyz"[a], p, dim_), f.unit});
            }
        open(s, startTime, columns);
        warnOfLocationsOutside(s);
        sample(s, false);
    }

private:
    void sample(const Scene& s, bool) override {
        const ParticleSet& set = sampled().particles;
        std::vector<double> row;
        const std::size_t nProbes = locations_.size();
        std::vector<std::vector<double>> values(fields_.size());
        for (std::size_t k = 0; k < nProbes; ++k) {
            // accumulate every field of this probe in one neighbour pass
            std::vector<Vec3> sums(fields_.size(), Vec3::Zero());
            std::vector<const std::vector<Scalar>*> scalars(fields_.size(), nullptr);
            std::vector<const std::vector<Vec3>*> vectors(fields_.size(), nullptr);
            for (std::size_t f = 0; f < fields_.size(); ++f) {
                const auto& name = fields_[f].name;
                if (fields_[f].vector) vectors[f] = name == "velocity" ? &set.velocity() : set.findVector(name);
                else
                    scalars[f] = name == "pressure"  ? &set.pressure()
                                 : name == "density" ? &set.density()
                                                     : set.findScalar(name);
            }
            const Scalar sum = shepardSum(s, locations_[k], [&](Index j, Scalar w) {
                for (std::size_t f = 0; f < fields_.size(); ++f) {
                    if (vectors[f]) sums[f] += w * (*vectors[f])[j];
                    else sums[f][0] += w * (*scalars[f])[j];
                }
            });
            for (std::size_t f = 0; f < fields_.size(); ++f) {
                const int n = fields_[f].vector ? dim_ : 1;
                for (int a = 0; a < n; ++a) values[f].push_back(sum > 0 ? double(sums[f][a] / sum) : notANumber);
            }
        }
        for (const auto& v : values) row.insert(row.end(), v.begin(), v.end());
        file_.writeRow(s.time, row);
    }

    void warnOfLocationsOutside(const Scene& s) const {
        Vec3 lo = Vec3::Constant(std::numeric_limits<Scalar>::max()), hi = -lo;
        const auto extend = [&](const std::vector<Vec3>& x) {
            for (const auto& p : x) {
                lo = lo.cwiseMin(p);
                hi = hi.cwiseMax(p);
            }
        };
        for (const auto& p : s.systems) extend(p->particles.position());
        if (!(lo[0] <= hi[0])) return; // no particle at all (refused before a run)
        const Scalar h = s.constants.supportRadius;
        const auto point = [&](const Vec3& p) {
            std::ostringstream o;
            o << "(" << p[0] << " " << p[1];
            if (dim_ == 3) o << " " << p[2];
            return o.str() + ")";
        };
        for (const auto& p : locations_) {
            bool outside = false;
            for (int a = 0; a < dim_; ++a) outside = outside || !(p[a] >= lo[a] - h && p[a] <= hi[a] + h);
            if (!outside) continue;
            std::ostringstream m;
            m << "probes '" << name_ << "': location " << point(p) << " lies outside the case (its particles span "
              << point(lo) << " to " << point(hi) << ", support radius " << h
              << "): no particle is near it; its columns hold nan until fluid comes within " << h << " of it";
            log::warning(locatedMessage(locationsWhere_, "", m.str(), "probeLocations"));
        }
    }

    // The unit of a fluid field for the header; "?" for a model's internal field of no fixed unit.
    std::string unitOf(const std::string& field) const {
        const std::string mass = massUnit(dim_), volume = dim_ == 3 ? "m^3" : "m^2";
        if (field == "pressure") return "Pa";
        if (field == "density") return "kg/m^3";
        if (field == "velocity" || field == "shiftingVelocity" || field == "viscousVelocity") return "m/s";
        if (field == "acceleration") return "m/s^2";
        if (field == "densityRate") return "kg/m^3/s";
        if (field == "densityGradient") return "kg/m^4";
        if (field == "vorticity") return "1/s";
        if (field == "surfaceNormal" || field == "shiftingZone") return "-";
        if (field == "wallMass") return mass;
        return "?";
    }

    struct Field {
        std::string name, label, unit;
        bool vector = false;
    };
    std::vector<std::string> fieldNames_;
    SourceLocation fieldsWhere_, locationsWhere_;
    std::vector<Vec3> locations_;
    std::vector<Field> fields_;
};
} // namespace

SPINDRIFT_PLUGIN(FunctionObject, Probes)
