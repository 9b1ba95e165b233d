// solverPerformance — a summary of an iterative pressure solver's convergence (PCISPH, PBF,
// ...). The core itself writes one row per step to
// postProcessing/solverPerformance/<startTime>/solverPerformance.dat (iterations, converged,
// maxDensityError, avgDensityError) when the pressure model is iterative; this function
// object reads those rows at the end of the run and writes their summary to
// postProcessing/<name>/<startTime>/solverPerformanceSummary.dat and to the log:
//   steps  averageIterations  maxIterations  notConverged  maxDensityError  averageDensityError
// (maxDensityError: the largest per-step value; averageDensityError: the mean of the per-step
// averages; both in % of ρ0, as the solver measures its own convergence). With an explicit pressure model there are no rows: it says so in the log and
// writes nothing.
//
//   solverPerformance { type solverPerformance; }
#include "FunctionObjectSupport.hpp"
#include "Log.hpp"
#include "Plugin.hpp"
#include "CaseWriter.hpp"

#include <fstream>
#include <sstream>

namespace {
using namespace spindrift;
using namespace spindrift::functionObjects;

class SolverPerformance final : public FunctionObject {
public:
    explicit SolverPerformance(const ModelContext& c) : caseDir_(c.caseDirectory), name_(c.name) {}

    void start(const Scene&, double startTime) override { startTime_ = startTime; }
    void execute(const Scene&, bool) override {}

    void end(const Scene& s) override {
        const auto folder = caseDir_ / "postProcessing" / "solverPerformance" / CaseWriter::timeName(startTime_);
        std::ifstream in(folder / "solverPerformance.dat");
        if (!in) {
            log::info("solverPerformance '" + name_ + "': the pressure model is not iterative (no rows)");
            return;
        }
        long steps = 0, notConverged = 0;
        double iterations = 0, maxIterations = 0, maxError = 0, avgError = 0;
        std::string line;
        while (std::getline(in, line)) {
            if (line.empty() || line[0] == '#') continue;
            std::istringstream row(line);
            double t, it, converged, maxE, avgE;
            if (!(row >> t >> it >> converged >> maxE >> avgE)) continue;
            ++steps;
            iterations += it;
            maxIterations = std::max(maxIterations, it);
            notConverged += converged == 0;
            maxError = std::max(maxError, maxE);
            avgError += avgE;
        }
        const double average = steps ? iterations / double(steps) : 0.0;
        PostProcessingFile summary(caseDir_, name_, startTime_,
                                   {{"steps", "-"},
                                    {"averageIterations", "-"},
                                    {"maxIterations", "-"},
                                    {"notConverged", "-"},
                                    {"maxDensityError", "%"},
                                    {"averageDensityError", "%"}},
                                   "solverPerformanceSummary");
        summary.writeRow(s.time, {double(steps), average, maxIterations, double(notConverged), maxError,
                                      steps ? avgError / double(steps) : 0.0});
        std::ostringstream o;
        o << "solverPerformance '" << name_ << "': " << steps << " steps, " << average << " iterations on average (max "
          << maxIterations << "), " << notConverged << " not converged, max density error " << maxError << "%";
        log::info(o.str());
    }

private:
    std::filesystem::path caseDir_;
    std::string name_;
    double startTime_ = 0;
};
} // namespace

SPINDRIFT_PLUGIN(FunctionObject, SolverPerformance)
