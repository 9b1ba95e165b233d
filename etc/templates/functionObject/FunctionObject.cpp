// Template function object plugin: the largest speed of the fluid systems after every step,
// written to postProcessing/<name>/<startTime>/<name>.dat.
//   controlDict:  functions { speed { type <this folder's name>; } }
#include "FunctionObject.hpp"
#include "Plugin.hpp"

#include <algorithm>

namespace {
using namespace spindrift;

class TemplateFunctionObject final : public FunctionObject {
public:
    explicit TemplateFunctionObject(const ModelContext& c) : caseDir_(c.caseDirectory), name_(c.name) {}

    void start(const Scene&, double startTime) override {
        file_ = PostProcessingFile(caseDir_, name_, startTime, {{"maxSpeed", "m/s"}}); // name, unit
    }

    void execute(const Scene& s, bool) override {
        double maxSpeed = 0;
        for (const ParticleSystem* fluid : s.ofRole(SystemRole::fluid)) {
            const auto& v = fluid->particles.velocity();
            maxSpeed = std::max(maxSpeed, parallelMax(fluid->ownedSize(), [&](std::size_t i) { return v[i].norm(); }));
        }
        file_.writeRow(s.time, {maxSpeed});
    }

private:
    std::filesystem::path caseDir_;
    std::string name_;
    PostProcessingFile file_;
};
} // namespace

SPINDRIFT_PLUGIN(FunctionObject, TemplateFunctionObject)
