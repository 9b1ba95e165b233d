// The case's set-up beyond the bad-input table (issue 33): overlapping fluid blocks merged,
// stacked blocks starting hydrostatic as one column, walls off the lattice placed and warned of
// (and the incompressible solvers running beside them), wall motions checked, moving walls that
// start inside the fluid, the memory a case may take.
#include "Case.hpp"
#include "Geometry.hpp"
#include "Log.hpp"
#include "Motion.hpp"
#include "Simulation.hpp"
#include "TestSupport.hpp"

#include <gtest/gtest.h>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <regex>

using namespace spindrift;
namespace fs = std::filesystem;

namespace {

// hydrostaticTank2D (Δx 0.01, a 0.2 × 0.3 column in a 0.2 × 0.4 container) in 'tmp'/name, its
// constant/geometry's fluid { } and the walls after the tank replaced by the given text.
fs::path tank(const test::TempDir& tmp, const std::string& name, const std::string& fluidBlocks,
              const std::string& moreWalls = "") {
    const fs::path dir = tmp.path() / name;
    copyCaseInput(fs::path(SPINDRIFT_SOURCE_DIR) / "tutorials/hydrostaticTank2D", dir);
    std::string g = test::readFile(dir / "constant/geometry");
    g = std::regex_replace(g, std::regex("\nfluid\\s*\\{\\s*water\\s*\\{[^}]*\\}\\s*\\}"), "\nfluid\n{\n" + fluidBlocks + "\n}",
                           std::regex_constants::format_first_only);
    g = std::regex_replace(g, std::regex("open    \\(yMax\\);\\s*\\}"), "open    (yMax);\n    }\n" + moreWalls,
                           std::regex_constants::format_first_only);
    std::ofstream(dir / "constant/geometry") << g;
    return dir;
}

void setPressureSolver(const fs::path& dir, const std::string& type, double endTime) {
    std::string schemes = test::readFile(dir / "system/sphSchemes");
    schemes = std::regex_replace(schemes, std::regex("\npressure\\s*\\{[^}]*\\}"), "\npressure\n{\n    type " + type + ";\n}",
                                 std::regex_constants::format_first_only);
    // (an incompressible solver has no sound speed for the artificial viscosity to take)
    schemes = std::regex_replace(schemes, std::regex("\nviscosity\\s*\\{[^}]*\\}"),
                                 "\nviscosity\n{\n    type artificial; alpha 0.1; soundSpeed 25;\n}",
                                 std::regex_constants::format_first_only);
    std::ofstream(dir / "system/sphSchemes") << schemes;
    std::string control = test::readFile(dir / "system/controlDict");
    control = std::regex_replace(control, std::regex("\nendTime[^;]*;"), "\nendTime " + std::to_string(endTime) + ";");
    control = std::regex_replace(control, std::regex("\nwriteInterval[^;]*;"), "\nwriteInterval 1;");
    std::ofstream(dir / "system/controlDict") << control;
}

// The smallest distance between a fluid particle and any other particle (fluid or wall) of the scene.
double closestToFluid(const Scene& s) {
    double closest = std::numeric_limits<double>::infinity();
    const auto& x = test::fluidOf(s).particles.position();
    for (std::size_t i = 0; i < x.size(); ++i) {
        for (std::size_t j = i + 1; j < x.size(); ++j) closest = std::min(closest, double((x[i] - x[j]).norm()));
        for (const ParticleSystem& w : test::walls(s))
            for (const auto& y : w.particles.position()) closest = std::min(closest, double((x[i] - y).norm()));
    }
    return closest;
}

const std::string water = "    water { type box; min (0 0 0); max (0.2 0.3 0); initialPressure hydrostatic; }\n";

} // namespace

TEST(CaseSetUp, OverlappingFluidBlocksAreMergedAndReportedOnce) {
    // issue 33.11: a second block identical to 'water' made 1,200 particles on 600 positions
    log::setQuiet(true);
    test::TempDir tmp;
    std::size_t single = 0;
    {
        Simulation sim(tank(tmp, "single", water));
        single = test::fluidOf(sim.scene()).size();
    }
    ASSERT_EQ(single, 600u);
    const std::string copy = "    copy { type box; min (0 0 0); max (0.2 0.3 0); initialPressure hydrostatic; }\n";
    testing::internal::CaptureStdout();
    {
        Simulation sim(tank(tmp, "twice", water + copy));
        EXPECT_EQ(test::fluidOf(sim.scene()).size(), single) << "each position filled once";
        EXPECT_GE(closestToFluid(sim.scene()), 0.999 * 0.01);
    }
    const std::string log = testing::internal::GetCapturedStdout();
    EXPECT_NE(log.find("fluid block 'copy' overlaps the blocks before it: 600 of its positions are filled already and "
                       "are not filled twice (0 particles added)"),
              std::string::npos)
        << log;
    EXPECT_EQ(log.find("overlaps", log.find("overlaps") + 1), std::string::npos) << "reported once";
    // a partial overlap: the union of the two blocks, 0.2 × 0.35 (700 positions)
    const std::string upper = "    upper { type box; min (0 0.1 0); max (0.2 0.35 0); }\n";
    {
        Simulation sim(tank(tmp, "partly", water + upper));
        EXPECT_EQ(test::fluidOf(sim.scene()).size(), 700u);
        EXPECT_GE(closestToFluid(sim.scene()), 0.999 * 0.01);
    }
    // off the lattice (shifted 0.3 Δx): no two particles nearer than Δx
    const std::string shifted = "    shifted { type box; min (0.003 0.103 0); max (0.193 0.353 0); }\n";
    {
        Simulation sim(tank(tmp, "shifted", water + shifted));
        EXPECT_GE(closestToFluid(sim.scene()), 0.999 * 0.01);
        EXPECT_GT(test::fluidOf(sim.scene()).size(), 600u);
    }
}

TEST(CaseSetUp, StackedHydrostaticBlocksStartAsOneColumn) {
    // issue 33.10: the column split into two stacked blocks started the lower one at 932 Pa at
    // the bottom instead of 2894, with a jump from 49 to 1913 Pa at the interface
    log::setQuiet(true);
    test::TempDir tmp;
    const auto pressureByPosition = [](const Simulation& sim) {
        std::map<std::pair<long, long>, double> p;
        const auto& x = test::fluidOf(sim.scene()).particles.position();
        const auto& pressure = test::fluidOf(sim.scene()).particles.pressure();
        for (std::size_t i = 0; i < x.size(); ++i) p[{std::lround(x[i][0] * 1e4), std::lround(x[i][1] * 1e4)}] = pressure[i];
        return p;
    };
    Simulation one(tank(tmp, "one", water));
    const std::string stacked =
        "    lower { type box; min (0 0 0); max (0.2 0.15 0); initialPressure hydrostatic; }\n"
        "    upper { type box; min (0 0.15 0); max (0.2 0.3 0); initialPressure hydrostatic; }\n";
    Simulation two(tank(tmp, "two", stacked));
    const auto a = pressureByPosition(one), b = pressureByPosition(two);
    ASSERT_EQ(a.size(), 600u);
    ASSERT_EQ(b.size(), a.size());
    double bottom = 0;
    for (const auto& [at, p] : a) {
        ASSERT_TRUE(b.count(at)) << at.first << " " << at.second;
        EXPECT_NEAR(b.at(at), p, 1e-9 * 3000 + test::tol(0, 2e-3)) << "at (" << at.first << ", " << at.second << ") e-4 m";
        bottom = std::max(bottom, p);
    }
    const double pressureTol = test::tol(1e-6, 1e-3); // float: ρ0 g depth to 7 digits
    EXPECT_NEAR(bottom, 1000 * 9.81 * 0.295, pressureTol); // ρ0 g (H − Δx/2) at the lowest row
    // a block separated from the one below by a gap of air keeps its own surface: the pool's top
    // row starts at ρ0 g Δx/2, the drop's bottom row at ρ0 g (its height − Δx/2)
    const std::string poolAndDrop =
        "    pool { type box; min (0 0 0); max (0.2 0.1 0); initialPressure hydrostatic; }\n"
        "    drop { type box; min (0.05 0.2 0); max (0.15 0.3 0); initialPressure hydrostatic; }\n";
    Simulation apart(tank(tmp, "apart", poolAndDrop));
    const auto c = pressureByPosition(apart);
    EXPECT_NEAR(c.at({1050, 950}), 1000 * 9.81 * 0.005, pressureTol);  // the pool's top row, under the drop
    EXPECT_NEAR(c.at({1050, 2050}), 1000 * 9.81 * 0.095, pressureTol); // the drop's bottom row
}

TEST(CaseSetUp, BoxWallOffTheLatticeIsPlacedOnItAndTheIncompressibleSolversRun) {
    // issue 33.18: a box 2.5 Δx wide starting half a spacing off the fluid's lattice left its last
    // column half a spacing from the water; pcisph, dfsph and iisph blew up at step 1
    log::setQuiet(true);
    // (issue 38: such a wall is refused unless the entry says it may be snapped)
    const std::string obstacle =
        "    obstacle { type box; min (0.105 0 0); max (0.13 0.1 0); layers 3; snapToLattice yes; }\n";
    for (const char* solver : {"pcisph", "dfsph", "iisph"}) {
        test::TempDir tmp;
        const fs::path dir = tank(tmp, "obstacle", water, obstacle);
        setPressureSolver(dir, solver, 0.02);
        log::setQuiet(false);
        testing::internal::CaptureStdout();
        std::unique_ptr<Simulation> made;
        try {
            made = std::make_unique<Simulation>(dir);
        } catch (const std::exception& e) {
            testing::internal::GetCapturedStdout();
            FAIL() << solver << ": " << e.what();
        }
        const std::string log = testing::internal::GetCapturedStdout();
        log::setQuiet(true);
        Simulation& sim = *made;
        EXPECT_NE(log.find("walls.obstacle: size along x (0.025) is not a multiple of particleSpacing 0.01; the wall "
                           "is placed at max x = 0.135 (snapToLattice)"),
                  std::string::npos)
            << log;
        EXPECT_GE(closestToFluid(sim.scene()), 0.999 * 0.01) << "no fluid particle nearer a wall than dx";
        RunSummary r;
        EXPECT_NO_THROW(r = sim.run()) << solver;
        EXPECT_GT(r.steps, 5) << solver;
        EXPECT_LT(r.maxDensityError, 0.05) << solver;
    }
}

TEST(CaseSetUp, WallMotionsThatAreNotFiniteOrAbsurdAreRefusedAtTheirKeyword) {
    // issue 33.8: each of these was accepted and wrote NaN positions or never moved the wall
    const auto errorOf = [](const std::string& text) -> std::string {
        try {
            Motion::read(Dictionary::fromString(text, "geometry"), 2, 0.0, 1.5);
        } catch (const InputError& e) {
            return e.what();
        }
        return "<no error>";
    };
    EXPECT_EQ(errorOf("type oscillating; amplitude 0.01; period 1e-310; direction (1 0 0);"),
              "geometry:1:35: error: motion period must be a positive normal number (at least 2.22507e-308), not "
              "1e-310 (keyword 'period')");
    EXPECT_EQ(errorOf("type oscillating; amplitude 0.01; period 1;\nstartTime -1e308; direction (1 0 0);"),
              "geometry:2:1: error: the oscillation would make 1e+308 periods from its startTime -1e+308 to the run's "
              "endTime 1.5, more than 1e+09 (its phase would lose all precision): start it nearer the run (keyword "
              "'startTime')");
    EXPECT_EQ(errorOf("type oscillating; amplitude 0.01; period 1e-12; direction (1 0 0);"),
              "geometry:1:35: error: the oscillation would make 1.5e+12 periods from its startTime 0 to the run's "
              "endTime 1.5, more than 1e+09 (its phase would lose all precision): use a longer period (keyword "
              "'period')");
    EXPECT_NE(errorOf("type oscillating; amplitude 1e303; period 1e-3; direction (1 0 0);").find("peak acceleration"),
              std::string::npos);
    EXPECT_NE(errorOf("type oscillating; amplitude 0.01; period 1; direction (0 0 0);").find("must not be zero"),
              std::string::npos);
    // a direction whose norm overflows is still a direction (in float, 1e38 overflows it)
    const std::string huge = test::singlePrecision ? "1e38" : "1e308";
    const auto m = Motion::read(Dictionary::fromString("type oscillating; amplitude 0.01; period 1; direction (" + huge +
                                                           " " + huge + " 0);",
                                                       "geometry"),
                                2, 0.0, 1.5);
    const Vec3 d = m->displacement(0.25);
    EXPECT_NEAR(d[0], 0.01 / std::sqrt(2.0), 1e-6);
    EXPECT_NEAR(d[1], 0.01 / std::sqrt(2.0), 1e-6);
}

TEST(CaseSetUp, AMovingWallDisplacedAtTheStartMustBeClearOfTheFluid) {
    // issue 33.9: movingPaddle2D from startTime 0.5 (or a motion's startTime -0.2) put the paddle
    // at its displaced position with water inside it: an error naming the wall
    log::setQuiet(true);
    test::TempDir tmp;
    const fs::path dir = tmp.path() / "paddle";
    copyCaseInput(fs::path(SPINDRIFT_SOURCE_DIR) / "tutorials/movingPaddle2D", dir);
    std::string control = test::readFile(dir / "system/controlDict");
    control = std::regex_replace(control, std::regex("\nstartTime[^;]*;"), "\nstartTime 0.5;");
    std::ofstream(dir / "system/controlDict") << control;
    try {
        Simulation sim(dir);
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("constant/geometry:39:9: error: wall 'paddle' starts at time 0.5 displaced by (0.1 0 0) by its "
                         "motion, where it overlaps "),
                  std::string::npos)
            << m;
        EXPECT_NE(m.find("particles of the fluid (block 'water' first)"), std::string::npos) << m;
        EXPECT_NE(m.find("(keyword 'motion')"), std::string::npos) << m;
    }
    // moved away from the water (a paddle pulled back), the run starts, and says so
    std::string geometry = test::readFile(dir / "constant/geometry");
    geometry = std::regex_replace(geometry, std::regex("velocity    \\(0.2 0 0\\)"), "velocity    (-0.01 0 0)");
    std::ofstream(dir / "constant/geometry") << geometry;
    log::setQuiet(false);
    testing::internal::CaptureStdout();
    try {
        Simulation sim(dir);
    } catch (const std::exception& e) {
        ADD_FAILURE() << e.what();
    }
    const std::string log = testing::internal::GetCapturedStdout();
    EXPECT_NE(log.find("wall 'paddle' starts at time 0.5 displaced by (-0.005 0 0) by its motion (clear of the fluid)"),
              std::string::npos)
        << log;
}

TEST(CaseSetUp, AvailableMemoryHonoursUlimitAndTheCgroups) {
    // issue 33.15: only /proc/meminfo was read; a cgroup's memory.max or `ulimit -v` below it
    // ended in bad_alloc
    test::TempDir tmp;
    const fs::path proc = tmp.path() / "proc", cgroup = tmp.path() / "cgroup";
    tmp.writeFile("proc/meminfo", "MemTotal:       16000000 kB\nMemFree:  100 kB\nMemAvailable:    8000000 kB\n");
    tmp.writeFile("proc/self/status", "Name: spindrift\nVmSize:\t  102400 kB\n");
    tmp.writeFile("proc/self/cgroup", "0::/user.slice/job\n");
    const double inf = std::numeric_limits<double>::infinity();
    MemoryLimit m = availableMemory(proc, cgroup, inf);
    EXPECT_DOUBLE_EQ(m.bytes, 8000000.0 * 1024);
    EXPECT_NE(m.source.find("/proc/meminfo"), std::string::npos) << m.source;
    // ulimit -v 1048576 (1 GiB) with 100 MiB of address space in use
    m = availableMemory(proc, cgroup, 1024.0 * 1024 * 1024);
    EXPECT_DOUBLE_EQ(m.bytes, 1024.0 * 1024 * 1024 - 102400.0 * 1024);
    EXPECT_NE(m.source.find("ulimit -v 1048576"), std::string::npos) << m.source;
    // cgroup v2: the job's limit, and a tighter one above it
    tmp.writeFile("cgroup/user.slice/job/memory.max", "max\n");
    tmp.writeFile("cgroup/user.slice/job/memory.current", "1000\n");
    tmp.writeFile("cgroup/user.slice/memory.max", "2147483648\n");
    tmp.writeFile("cgroup/user.slice/memory.current", "1073741824\n");
    m = availableMemory(proc, cgroup, inf);
    EXPECT_DOUBLE_EQ(m.bytes, 1073741824.0);
    EXPECT_NE(m.source.find((cgroup / "user.slice/memory.max").string()), std::string::npos) << m.source;
    // cgroup v1's memory controller
    tmp.writeFile("proc/self/cgroup", "4:memory:/docker/abc\n0::/\n");
    tmp.writeFile("cgroup/memory/docker/abc/memory.limit_in_bytes", "536870912\n");
    tmp.writeFile("cgroup/memory/docker/abc/memory.usage_in_bytes", "268435456\n");
    tmp.writeFile("cgroup/memory/memory.limit_in_bytes", "9223372036854771712\n"); // no limit
    m = availableMemory(proc, cgroup, inf);
    EXPECT_DOUBLE_EQ(m.bytes, 268435456.0);
    EXPECT_NE(m.source.find("memory.limit_in_bytes"), std::string::npos) << m.source;
}

TEST(CaseSetUp, AMovingWallThatIsNotFiniteIsABlowUp) {
    // issue 33.8: NaN wall positions were written at every time and the run ended with exit 0.
    // The motions are checked at set-up; the blow-up check holds the walls' positions too.
    log::setQuiet(true);
    test::TempDir tmp;
    const fs::path dir = tmp.path() / "paddle";
    copyCaseInput(fs::path(SPINDRIFT_SOURCE_DIR) / "tutorials/movingPaddle2D", dir);
    std::string control = test::readFile(dir / "system/controlDict");
    control = std::regex_replace(control, std::regex("\nendTime[^;]*;"), "\nendTime 0.01;");
    std::ofstream(dir / "system/controlDict") << control;
    Simulation sim(dir);
    ParticleSystem* paddle = sim.scene().find("paddle");
    ASSERT_NE(paddle, nullptr);
    paddle->initialPosition[0][0] = std::numeric_limits<Scalar>::quiet_NaN();
    try {
        sim.run();
        ADD_FAILURE() << "no blow-up";
    } catch (const BlowUpError& e) {
        EXPECT_NE(std::string(e.what()).find("blow-up at step 1, time "), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(": wall 'paddle' is displaced by ("), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("beyond the domain or not finite"), std::string::npos) << e.what();
    }
}
