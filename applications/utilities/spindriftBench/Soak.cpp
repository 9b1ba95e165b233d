// spindriftBench -soak N: kill -9 at a random moment and restart, N times, each restart run to
// the end and its end state compared bit for bit with an uninterrupted run (issue 21).
#include "Soak.hpp"

#include "CaseWriter.hpp"

#include <chrono>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <random>
#include <sstream>

namespace fs = std::filesystem;

namespace spindrift::bench {
namespace {

std::string fileBytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) return "<missing>";
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// What a finished run leaves: its time names, and the bytes of the end state (the newest
// time's fluid.vtp and uniform/time) and of the .pvd.
struct EndState {
    std::vector<std::string> times;
    std::string fluid, time, collection;
};

EndState endState(const fs::path& caseDir) {
    EndState e;
    for (const auto& [value, name] : CaseWriter(caseDir).existingTimes()) e.times.push_back(name);
    if (e.times.empty()) return e;
    e.fluid = fileBytes(caseDir / e.times.back() / "fluid.vtp");
    e.time = fileBytes(caseDir / e.times.back() / "uniform/time");
    e.collection = fileBytes(CaseWriter(caseDir).collectionFile());
    return e;
}

// Why two end states differ (empty: they are the same, byte for byte).
std::string difference(const EndState& reference, const EndState& e) {
    if (e.times != reference.times) {
        std::string a, b;
        for (const auto& t : reference.times) a += " " + t;
        for (const auto& t : e.times) b += " " + t;
        return "times" + b + " instead of" + a;
    }
    if (e.fluid != reference.fluid) return "fluid.vtp of " + e.times.back() + " differs";
    if (e.time != reference.time) return "uniform/time of " + e.times.back() + " differs";
    if (e.collection != reference.collection) return "the .pvd differs";
    return {};
}

} // namespace

int runSoak(const SoakSettings& settings) {
    const auto start = std::chrono::steady_clock::now();
    const fs::path soakDir = settings.output / "soak";
    fs::create_directories(soakDir);
    // a fresh copy of the case with the overrides, restarting from its newest time when it has
    // one (the first start, with none, starts from startTime)
    const auto prepare = [&](const fs::path& dir) {
        fs::remove_all(dir);
        copyCaseInput(settings.caseDir, dir);
        CaseDictionaries dicts(dir);
        dicts.apply(settings.overrides, settings.presets);
        dicts.apply(Override{"startFrom", "latestTime"}, nullptr);
        dicts.write();
    };
    const auto solve = [&](const fs::path& dir, const std::string& log, double killAfter) {
        return runProcess({settings.solver.string(), "-case", ".", "-threads", std::to_string(settings.threads)}, dir,
                          dir / log, settings.env, killAfter, SIGKILL);
    };

    const fs::path referenceDir = soakDir / "reference";
    prepare(referenceDir);
    const ProcessResult reference = solve(referenceDir, "log.spindrift", 0);
    if (reference.status != 0)
        throw std::runtime_error("the uninterrupted run failed (exit status " + std::to_string(reference.status) +
                                 "): " + lastLine(referenceDir / "log.spindrift"));
    const EndState expected = endState(referenceDir);
    if (expected.times.size() < 2) throw std::runtime_error("the uninterrupted run wrote fewer than 2 times");
    std::cout << "soak: the uninterrupted run took " << std::setprecision(3) << reference.seconds << " s and wrote "
              << expected.times.size() << " times (" << expected.times.front() << " to " << expected.times.back()
              << "); " << settings.count << " runs killed (SIGKILL) at a random moment, restarted and run to the end, "
              << "seed " << settings.seed << std::endl;

    std::mt19937_64 random(settings.seed);
    // the kill: anywhere from the start of the process (set-up) to near the end of the
    // uninterrupted run's duration, the shortest measured (a run that ends before its kill is
    // restarted all the same, and counted)
    std::uniform_real_distribution<double> fraction(0.0, 0.95);
    double duration = reference.seconds;
    int identical = 0, killedRunning = 0, endedFirst = 0;
    const fs::path runDir = soakDir / "run";
    for (int k = 1; k <= settings.count; ++k) {
        prepare(runDir);
        const double killAfter = std::max(fraction(random) * duration, 1e-3);
        const ProcessResult first = solve(runDir, "log.killed", killAfter);
        if (first.timedOut) {
            ++killedRunning;
        } else {
            ++endedFirst;
            duration = std::min(duration, first.seconds);
        }
        const ProcessResult restart = solve(runDir, "log.restart", 0);
        std::string problem;
        if (!first.timedOut && first.status != 0)
            problem = "the run before the kill failed (exit status " + std::to_string(first.status) + ")";
        else if (restart.status != 0)
            problem = "the restart failed (exit status " + std::to_string(restart.status) +
                      "): " + lastLine(runDir / "log.restart");
        else
            problem = difference(expected, endState(runDir));
        if (problem.empty()) {
            ++identical;
        } else {
            const fs::path kept = soakDir / ("failed-" + std::to_string(k));
            fs::remove_all(kept);
            fs::rename(runDir, kept);
            std::cout << "soak: run " << k << " (kill after " << std::setprecision(3) << killAfter
                      << " s): " << problem << "; kept in " << kept.string() << std::endl;
        }
        if (k % 20 == 0 || k == settings.count)
            std::cout << "soak: " << identical << "/" << k << " bit-identical so far" << std::endl;
    }
    fs::remove_all(runDir);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << "soak: " << identical << "/" << settings.count << " bit-identical (" << killedRunning
              << " killed while running, " << endedFirst << " ended before the kill), " << std::fixed
              << std::setprecision(1) << seconds << " s" << std::endl;
    return identical == settings.count ? 0 : 1;
}

} // namespace spindrift::bench
