// forces — the force and moment the fluid exerts on walls and bodies, as OpenFOAM's forces
// function object reports them: the reactions of the models' boundary pair terms (Reactions.hpp;
// pressure, viscous and other parts apart), summed over the systems named in `patches`.
//
//   forces1
//   {
//       type          forces;
//       patches       (tank);      // wall or body systems (constant/geometry); default: every one
//       CofR          (0 0 0);     // the point the moment is taken about [m]
//       writeControl  timeStep;    // timeStep | runTime | writeTime (FunctionObjectSupport.hpp)
//       writeInterval 1;
//   }
//
// Output postProcessing/<name>/<startTime>/force.dat and moment.dat, one row per sample:
//   Time total_x total_y total_z pressure_x ... viscous_x ... other_x ...
// in N and N m (in 2D per unit depth: N/m and N m/m). The forces are those of the step's last
// force evaluation (symplecticEuler: at the start of the step; the multi-step integrators: at its
// end state). A row is written at the first sample after the start.
#include "FunctionObjectSupport.hpp"
#include "Plugin.hpp"

namespace {
using namespace spindrift;
using namespace spindrift::functionObjects;

class Forces final : public FunctionObject {
public:
    explicit Forces(const ModelContext& c)
        : name_(c.name), caseDir_(c.caseDirectory), dimension_(c.physics.dimension), control_(c.dict),
          patches_(c.dict.getOrDefault<std::vector<std::string>>("patches", {})),
          patchesWhere_(c.dict.found("patches") ? c.dict.locationOf("patches") : c.dict.where()) {
        const Vec3 cofr = c.dict.getOrDefault<Vec3>("CofR", Vec3::Zero());
        if (!cofr.allFinite()) throw InputError(c.dict.locationOf("CofR"), "CofR must be finite", "CofR");
        centre_ = cofr.cast<double>();
    }

    void require(Scene& s) override {
        systems_.clear();
        if (patches_.empty()) {
            for (const ParticleSystem* b : s.boundaries()) systems_.push_back(b->index);
        } else {
            for (const std::string& name : patches_) {
                const ParticleSystem* p = s.find(name);
                if (!p || !p->isBoundary()) {
                    std::string names;
                    for (const ParticleSystem* b : s.boundaries()) names += (names.empty() ? "" : " ") + b->name();
                    throw InputError(patchesWhere_, "forces '" + name_ + "': '" + name +
                                                        "' is not a wall or body of the case; walls and bodies: (" +
                                                        names + ")", "patches");
                }
                systems_.push_back(p->index);
            }
        }
        if (systems_.empty())
            throw InputError(patchesWhere_, "forces '" + name_ + "': the case has no wall or body to report on", "patches");
        for (std::size_t k : systems_) s.reactions.want(k);
    }

    void start(const Scene&, double startTime) override {
        // per metre of depth in 2D
        const std::string perDepth = dimension_ == 2 ? "/m" : "";
        const auto columns = [&](const std::string& unit) {
            std::vector<PostProcessingColumn> c;
            for (const char* part : {"total", "pressure", "viscous", "other"})
                for (int a = 0; a < 3; ++a) c.push_back({std::string(part) + "_" + "xyz"[a], unit + perDepth});
            return c;
        };
        force_ = PostProcessingFile(caseDir_, name_, startTime, columns("N"), "force");
        moment_ = PostProcessingFile(caseDir_, name_, startTime, columns("N m"), "moment");
        control_.start(startTime);
    }

    void execute(const Scene& s, bool writeTime) override {
        if (!control_.due(s.time, writeTime)) return;
        std::vector<double> force, moment;
        const auto add = [&](const Wrench& w) {
            for (int a = 0; a < 3; ++a) force.push_back(w.force[a]);
            const Wrench::V3 m = w.momentAbout(centre_);
            for (int a = 0; a < 3; ++a) moment.push_back(m[a]);
        };
        Wrench total, parts[forceKinds];
        for (std::size_t k : systems_)
            for (std::size_t kind = 0; kind < forceKinds; ++kind) {
                const Wrench& w = s.reactions.of(k, ForceKind(kind));
                parts[kind] += w;
                total += w;
            }
        add(total);
        for (const Wrench& w : parts) add(w);
        force_.writeRow(s.time, force);
        moment_.writeRow(s.time, moment);
    }

private:
    std::string name_;
    std::filesystem::path caseDir_;
    int dimension_;
    SampleControl control_;
    std::vector<std::string> patches_;
    SourceLocation patchesWhere_;
    Wrench::V3 centre_;
    std::vector<std::size_t> systems_;
    PostProcessingFile force_, moment_;
};
} // namespace

SPINDRIFT_PLUGIN(FunctionObject, Forces)
