// Restarts continue bit for bit: a run 0 → T equals 0 → T/2 plus `startFrom latestTime`
// T/2 → T, for every integrator and pressure model found on the plugin path, and whatever the
// thread count. Blow-ups stop with a message and the last good state written; onBlowUp
// reduceDeltaT retries.
#include "Case.hpp"
#include "Log.hpp"
#include "Simulation.hpp"
#include "TestSupport.hpp"

#include <gtest/gtest.h>
#include <fstream>
#include <sstream>
#include <limits>
#ifdef _OPENMP
#include <omp.h>
#endif

using namespace spindrift;
namespace fs = std::filesystem;

namespace {

void setThreads(int n) {
#ifdef _OPENMP
    omp_set_num_threads(n);
#else
    (void)n;
#endif
}

void editDictionary(const fs::path& file, const std::vector<std::pair<std::string, std::string>>& entries) {
    Dictionary d = Dictionary::fromFile(file);
    for (const auto& [key, value] : entries) d.set(key, value);
    if (d.found("pressureSolvers") && d.found("pressure") && d.isDict("pressure"))
        d.remove("pressureSolvers"); // the tutorial's menu of solvers, replaced by an explicit choice
    std::ofstream(file) << d.toString();
}

// A small dam break (about 450 particles) with the given integrator and pressure model.
fs::path makeCase(const fs::path& dir, const std::string& integrator, const std::string& pressure, double endTime,
                  const std::string& pressureOptions = "") {
    copyCaseInput(fs::path(SPINDRIFT_SOURCE_DIR) / "tutorials/damBreak2D", dir);
    editDictionary(dir / "constant/fluidProperties", {{"particleSpacing", "0.0047625"}}); // a/12
    editDictionary(dir / "system/controlDict", {{"endTime", std::to_string(endTime)}, {"writeInterval", "0.005"},
                                                 {"maxCo", "0.1"}});
    editDictionary(dir / "system/sphSchemes",
                   {{"integrator", "{ type " + integrator + "; }"}, {"pressure", "{ type " + pressure + "; " + pressureOptions + " }"},
                    {"viscosity", "{ type laminar; }"}}); // needs no sound speed: works with every solver
    return dir;
}

ParticleSet finalState(const fs::path& caseDir) {
    CaseWriter writer(caseDir);
    const auto times = writer.existingTimes();
    return readVtp(caseDir / times.back().second / "fluid.vtp");
}

struct Combination {
    std::string integrator, pressure, options; // options: more entries of the pressure dictionary
    std::string name() const {
        std::string n = integrator;
        n += '_';
        n += pressure;
        if (!options.empty()) {
            n += '_';
            n.append(options, 0, options.find(' '));
        }
        return n;
    }
};
void PrintTo(const Combination& c, std::ostream* os) { *os << c.integrator << " + " << c.pressure << " " << c.options; }

// Whether integrator i applies the result of pressure model p exactly (the pairings the core
// accepts; the others are refused at set-up, RefusesAPressureResultTheIntegratorCannotApply).
bool applies(const std::string& integrator, const std::string& pressure) {
    const auto physics = test::physicsFor(2);
    return test::createModel<Integrator>("type " + integrator + ";", physics)
        ->applies(test::createModel<PressureModel>("type " + pressure + ";", physics)->result());
}

std::vector<Combination> combinations() {
    // quiet: the models made here log their defaults while gtest lists the tests, and ctest's
    // test discovery would read those lines as test names
    log::setQuiet(true);
    std::vector<Combination> out;
    auto& registry = ModelRegistry::instance();
    for (const auto& i : registry.available("integrator"))
        for (const auto& p : registry.available("pressure"))
            if (applies(i, p)) out.push_back({i, p, ""});
    out.push_back({"symplecticEuler", "dfsph", "checkPositions yes;"}); // its extra restart field
    return out;
}

class RestartTest : public testing::TestWithParam<Combination> {};

TEST_P(RestartTest, ContinuesBitForBitWithAnyThreadCount) {
    log::setQuiet(true);
    const auto& [integrator, pressure, options] = GetParam();
    test::TempDir tmp;
    const double T = 0.01;
    // uninterrupted, one thread
    const fs::path whole = makeCase(tmp.path() / "whole", integrator, pressure, T, options);
    setThreads(1);
    {
        Simulation sim(whole);
        sim.run();
    }
    // first half, then a restart, with two threads
    const fs::path split = makeCase(tmp.path() / "split", integrator, pressure, T / 2, options);
    setThreads(2);
    long firstSteps = 0;
    {
        Simulation sim(split);
        firstSteps = sim.run().steps;
    }
    editDictionary(split / "system/controlDict", {{"startFrom", "latestTime"}, {"endTime", std::to_string(T)}});
    {
        Simulation sim(split);
        EXPECT_EQ(sim.scene().step, firstSteps) << "the step index is restored";
        sim.run();
    }
    setThreads(1);

    const ParticleSet a = finalState(whole), b = finalState(split);
    ASSERT_EQ(a.size(), b.size());
    ASSERT_GT(a.size(), 100u);
    EXPECT_EQ(a.id(), b.id());
    EXPECT_EQ(a.position(), b.position()) << "positions differ";
    EXPECT_EQ(a.velocity(), b.velocity()) << "velocities differ";
    EXPECT_EQ(a.density(), b.density());
    EXPECT_EQ(a.pressure(), b.pressure());
    EXPECT_EQ(CaseWriter(whole).existingTimes().size(), CaseWriter(split).existingTimes().size());
    // every field a model registered for restarts is in the time directory
    for (const auto& f : a.scalarFields()) EXPECT_EQ(f->data, *b.findScalar(f->name)) << f->name;
    for (const auto& f : a.vectorFields()) EXPECT_EQ(f->data, *b.findVector(f->name)) << f->name;
}

INSTANTIATE_TEST_SUITE_P(EveryIntegratorAndPressureModel, RestartTest, testing::ValuesIn(combinations()),
                         [](const auto& info) { return info.param.name(); });

// A solver whose result is a change of position (pbf: Δx/Δt²) or of velocity (dfsph: Δv/Δt) with an
// integrator that cannot apply it exactly is refused before anything is written, naming both.
TEST(Contract, RefusesAPressureResultTheIntegratorCannotApply) {
    log::setQuiet(true);
    test::TempDir tmp;
    for (const std::string pressure : {"pbf", "relaxedPbf", "dfsph"})
        for (const std::string integrator : {"leapfrog", "velocityVerlet", "pereaCordero"}) {
            const fs::path dir = makeCase(tmp.path() / (pressure + integrator), integrator, pressure, 0.01);
            try {
                Simulation sim(dir);
                FAIL() << pressure << " with " << integrator << " was accepted";
            } catch (const InputError& e) {
                const std::string m = e.what();
                EXPECT_NE(m.find("'" + pressure + "'"), std::string::npos) << m;
                EXPECT_NE(m.find("'" + integrator + "'"), std::string::npos) << m;
                EXPECT_NE(m.find("symplecticEuler"), std::string::npos) << m;
                EXPECT_NE(m.find("sphSchemes"), std::string::npos) << "names the file: " << m;
            }
            EXPECT_FALSE(fs::exists(dir / "0")) << "nothing written";
        }
    // ... and accepted with symplectic Euler
    EXPECT_NO_THROW(Simulation(makeCase(tmp.path() / "ok", "symplecticEuler", "pbf", 0.01)));
}

fs::path tooLargeTimeStep(const fs::path& dir, const std::string& onBlowUp) {
    copyCaseInput(fs::path(SPINDRIFT_SOURCE_DIR) / "tutorials/hydrostaticTank2D", dir);
    // about 20 times the stable step, fixed
    editDictionary(dir / "system/controlDict", {{"adjustTimeStep", "no"}, {"deltaT", "3e-3"}, {"endTime", "0.05"},
                                                 {"writeInterval", "0.05"}, {"onBlowUp", onBlowUp}});
    return dir;
}

TEST(BlowUp, StopsNamingStepTimeAndParticleAndWritesTheLastGoodState) {
    log::setQuiet(true);
    test::TempDir tmp;
    const fs::path caseDir = tooLargeTimeStep(tmp.path() / "case", "stop");
    Simulation sim(caseDir);
    try {
        sim.run();
        FAIL() << "expected a blow-up";
    } catch (const std::runtime_error& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("blow-up at step "), std::string::npos) << m;
        EXPECT_NE(m.find(", time "), std::string::npos) << m;
        EXPECT_NE(m.find(": particle "), std::string::npos) << m;
        EXPECT_NE(m.find("The last good state (time "), std::string::npos) << m;
    }
    const auto times = CaseWriter(caseDir).existingTimes();
    ASSERT_GE(times.size(), 2u) << "0 and the last good state";
    const ParticleSet good = readVtp(caseDir / times.back().second / "fluid.vtp");
    for (std::size_t i = 0; i < good.size(); ++i) {
        ASSERT_TRUE(good.position()[i].allFinite());
        ASSERT_LT((good.density()[i] - 1000) / 1000, 0.2) << "the written state is below the blow-up bound";
    }
}

// The times written after the last good state (a density blow-up rolls back two steps, past
// a written one) are removed: the newest time is the good state, so 'startFrom latestTime'
// restarts from it (issue 21, item 5).
TEST(BlowUp, LeavesTheLastGoodStateAsTheNewestTime) {
    log::setQuiet(true);
    test::TempDir tmp;
    const fs::path caseDir = tooLargeTimeStep(tmp.path() / "case", "stop");
    editDictionary(caseDir / "system/controlDict", {{"writeInterval", "3e-3"}}); // every step
    std::string message;
    try {
        Simulation sim(caseDir);
        sim.run();
        FAIL() << "expected a blow-up";
    } catch (const std::runtime_error& e) {
        message = e.what();
    }
    const std::string marker = "The last good state (time ";
    const auto at = message.find(marker);
    ASSERT_NE(at, std::string::npos) << message;
    const std::string good = message.substr(at + marker.size(), message.find(')', at) - at - marker.size());
    const auto times = CaseWriter(caseDir).existingTimes();
    ASSERT_FALSE(times.empty());
    EXPECT_EQ(times.back().second, good) << message;
    const std::string pvd = test::readFile(caseDir / "case.pvd");
    EXPECT_NE(pvd.find("file=\"" + good + "/fluid.vtp\""), std::string::npos);
    for (const auto& entry : fs::directory_iterator(caseDir))
        EXPECT_EQ(entry.path().filename().string().find(".removed"), std::string::npos);
    // the step index of the good state
    const Dictionary t = Dictionary::fromFile(caseDir / good / "uniform/time");
    const std::string stepText = "blow-up at step ";
    const long blowUpStep = std::stol(message.substr(message.find(stepText) + stepText.size()));
    EXPECT_LT(t.get<long>("index"), blowUpStep);
}

TEST(BlowUp, ReduceDeltaTRetriesAndFinishes) {
    log::setQuiet(true);
    test::TempDir tmp;
    Simulation sim(tooLargeTimeStep(tmp.path() / "case", "reduceDeltaT"));
    const RunSummary r = sim.run();
    EXPECT_NEAR(r.endTime, 0.05, 1e-12);
    EXPECT_GT(r.steps, 17) << "some steps were taken with a reduced deltaT";
}

// After a retry the reduced Δt is kept: held for the hold steps, then growing by at most 1.1×
// a step (issue 21, item 5: it jumped back from 0.000625 to 0.005). The cap is in the written
// times' uniform/time, so that a restart from one of them continues with it, bit for bit.
TEST(BlowUp, ReducedDeltaTIsHeldAfterARetryThenGrowsGradually) {
    test::TempDir tmp;
    const fs::path caseDir = tooLargeTimeStep(tmp.path() / "case", "reduceDeltaT");
    // (writeControl runTime: no step shortened to land on a write time, only the last on endTime)
    editDictionary(caseDir / "system/controlDict",
                   {{"logInterval", "1"}, {"writeControl", "runTime"}, {"writeInterval", "0.003"}});
    log::setQuiet(false);
    testing::internal::CaptureStdout();
    {
        Simulation sim(caseDir);
        EXPECT_NEAR(sim.run().endTime, 0.05, 1e-12);
    }
    const std::string out = testing::internal::GetCapturedStdout();
    log::setQuiet(true);
    // the step sizes logged, and each retry's cap
    std::istringstream lines(out);
    const std::string retrying = "retrying with deltaT ", stepLine = "Time = ", deltaT = "  deltaT ";
    int retries = 0, held = 0, grown = 0;
    double cap = 0, previous = 0;
    int sinceRetry = -1;
    for (std::string line; std::getline(lines, line);) {
        if (const auto at = line.find(retrying); at != std::string::npos) {
            cap = std::stod(line.substr(at + retrying.size()));
            EXPECT_NE(line.find("held for 20 steps, then growing by at most 1.1x a step"), std::string::npos) << line;
            ++retries;
            sinceRetry = 0;
            continue;
        }
        if (line.rfind(stepLine, 0) != 0 || sinceRetry < 0) continue;
        const double dt = std::stod(line.substr(line.find(deltaT) + deltaT.size()));
        const double time = std::stod(line.substr(stepLine.size()));
        ++sinceRetry;
        if (time > 0.05 - 2 * cap) { // the last steps, shortened to land on endTime
            EXPECT_LE(dt, cap * 1.005) << line;
        } else if (sinceRetry <= 20) { // (3 digits in the log)
            EXPECT_NEAR(dt, cap, 0.005 * cap) << "step " << sinceRetry << " after the retry to " << cap << ": " << line;
            ++held;
        } else {
            EXPECT_LE(dt, 1.1 * previous * 1.01) << line;
            grown += dt > previous * 1.01;
        }
        previous = dt;
    }
    EXPECT_GE(retries, 1) << out;
    EXPECT_GE(held, 20) << out;
    EXPECT_GE(grown, 3) << "the cap grows back after the hold: " << out;

    // a time written while the cap holds keeps it; restarting there continues bit for bit
    const auto times = CaseWriter(caseDir).existingTimes();
    std::string capped;
    for (const auto& [value, name] : times)
        if (capped.empty() && name != "0" && Dictionary::fromFile(caseDir / name / "uniform/time").found("blowUpDeltaTCap"))
            capped = name;
    ASSERT_FALSE(capped.empty()) << "no written time holds the cap";
    const fs::path restarted = tmp.path() / "restarted";
    copyCaseInput(caseDir, restarted);
    for (const auto& [value, name] : times)
        if (value <= std::stod(capped)) fs::copy(caseDir / name, restarted / name, fs::copy_options::recursive);
    editDictionary(restarted / "system/controlDict", {{"startFrom", "latestTime"}});
    {
        Simulation sim(restarted);
        EXPECT_EQ(CaseWriter::timeName(sim.scene().time), capped);
        sim.run();
    }
    const ParticleSet a = finalState(caseDir), b = finalState(restarted);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(a.position(), b.position()) << "the restart from " << capped << " differs";
    EXPECT_EQ(a.velocity(), b.velocity());
}

// The end state is written also when endTime is off the write schedule (issue 21, item 9).
TEST(EndState, WrittenOffTheWriteSchedule) {
    log::setQuiet(true);
    test::TempDir tmp;
    const fs::path caseDir = makeCase(tmp.path() / "case", "symplecticEuler", "wcsph", 0.0075);
    Simulation sim(caseDir);
    const RunSummary r = sim.run();
    std::vector<std::string> names;
    for (const auto& [value, name] : CaseWriter(caseDir).existingTimes()) names.push_back(name);
    EXPECT_EQ(names, (std::vector<std::string>{"0", "0.005", "0.0075"}));
    EXPECT_EQ(Dictionary::fromFile(caseDir / "0.0075/uniform/time").get<long>("index"), r.steps);
    EXPECT_NE(test::readFile(caseDir / "case.pvd").find("0.0075/fluid.vtp"), std::string::npos);

    // writeControl timeStep: the last step, not a multiple of writeInterval, is written too
    const fs::path steps = makeCase(tmp.path() / "steps", "symplecticEuler", "wcsph", 0.002);
    editDictionary(steps / "system/controlDict", {{"writeControl", "timeStep"}, {"writeInterval", "1000"}});
    Simulation(steps).run();
    EXPECT_TRUE(fs::exists(steps / "0.002/fluid.vtp"));
}

// Restart input is validated (issue 21, item 7): the newest time with a value that is not
// finite, or without uniform/time (its step index), is skipped with a warning for the time
// before, whose step index is kept; with no usable time the error names the problem.
TEST(RestartInput, FallsBackToThePreviousCompleteTime) {
    log::setQuiet(true);
    test::TempDir tmp;
    const fs::path caseDir = makeCase(tmp.path() / "case", "symplecticEuler", "wcsph", 0.01);
    Simulation(caseDir).run();
    editDictionary(caseDir / "system/controlDict", {{"startFrom", "latestTime"}, {"endTime", "0.015"}});
    const long index005 = Dictionary::fromFile(caseDir / "0.005/uniform/time").get<long>("index");
    ASSERT_GT(index005, 0);
    const auto restartsFrom = [&](double time, long step) {
        Simulation sim(caseDir);
        EXPECT_DOUBLE_EQ(sim.scene().time, time);
        EXPECT_EQ(sim.scene().step, step);
    };

    // a NaN position in the newest fluid.vtp
    ParticleSet saved = readVtp(caseDir / "0.01/fluid.vtp");
    const ParticleSet intact = readVtp(caseDir / "0.01/fluid.vtp");
    saved.position()[7][1] = std::numeric_limits<Scalar>::quiet_NaN();
    writeVtp(caseDir / "0.01/fluid.vtp", saved);
    restartsFrom(0.005, index005);

    // the newest without uniform/time: not restarted from with the step index reset
    writeVtp(caseDir / "0.01/fluid.vtp", intact);
    fs::remove(caseDir / "0.01/uniform/time");
    restartsFrom(0.005, index005);

    // no usable time at all: a clear error
    for (const std::string name : {"0", "0.005"}) fs::remove(caseDir / name / "uniform/time");
    try {
        Simulation sim(caseDir);
        FAIL() << "restarted without any usable time";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("no time directory to restart from (time 0.01: uniform/time (its step index) is missing)"),
                  std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("(keyword 'startFrom')"), std::string::npos) << e.what();
    }
}

// A newest time cut short (fluid.vtp truncated in half: a disk that filled, a copy
// interrupted) is skipped with a warning naming it; the run restarts from the time before,
// rewrites the cut time and ends where an uninterrupted run ends, bit for bit (issue 21, item 7).
TEST(RestartInput, FallsBackFromATruncatedNewestTimeAndContinuesToTheEnd) {
    log::setQuiet(true);
    test::TempDir tmp;
    const fs::path whole = makeCase(tmp.path() / "whole", "symplecticEuler", "wcsph", 0.015);
    Simulation(whole).run();
    const fs::path caseDir = makeCase(tmp.path() / "case", "symplecticEuler", "wcsph", 0.01);
    Simulation(caseDir).run();
    const fs::path cut = caseDir / "0.01/fluid.vtp";
    fs::resize_file(cut, fs::file_size(cut) / 2);
    editDictionary(caseDir / "system/controlDict", {{"startFrom", "latestTime"}, {"endTime", "0.015"}});

    log::setQuiet(false);
    testing::internal::CaptureStdout();
    RunSummary r;
    {
        Simulation sim(caseDir);
        EXPECT_DOUBLE_EQ(sim.scene().time, 0.005);
        r = sim.run();
    }
    const std::string out = testing::internal::GetCapturedStdout();
    log::setQuiet(true);
    EXPECT_NE(out.find("--> Warning: startFrom latestTime: cannot restart from time 0.01 ("), std::string::npos) << out;
    EXPECT_NE(out.find("fluid.vtp"), std::string::npos) << out;
    EXPECT_NE(out.find("); trying the time before"), std::string::npos) << out;
    EXPECT_NE(out.find("Restarting from time 0.005 "), std::string::npos) << out;
    EXPECT_NEAR(r.endTime, 0.015, 1e-12);
    std::vector<std::string> names;
    for (const auto& [value, name] : CaseWriter(caseDir).existingTimes()) names.push_back(name);
    EXPECT_EQ(names, (std::vector<std::string>{"0", "0.005", "0.01", "0.015"}));
    const ParticleSet rewritten = readVtp(cut), reference = readVtp(whole / "0.01/fluid.vtp");
    EXPECT_EQ(rewritten.position(), reference.position()) << "0.01 is written again, whole";
    const ParticleSet a = finalState(whole), b = finalState(caseDir);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(a.position(), b.position());
    EXPECT_EQ(a.velocity(), b.velocity());
    EXPECT_EQ(a.density(), b.density());
}

} // namespace
