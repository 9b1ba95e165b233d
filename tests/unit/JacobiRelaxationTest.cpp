// The Jacobi-type pressure solvers (dfsph, iisph, pbf) with a wide kernel: Wendland C2 at a
// support of 4Δx in 2D, whose largest lattice correction gain (2.84) is above the 2 where the
// paper's relaxations diverge. The solvers hold their relaxation to a gain of 1.8 on every wave
// (boundedJacobiRelaxation, plugins/pressure/common/LatticePrototype.hpp); without it iisph blew up
// in this tank at step 8 (dfsph at the Colagrossi dam break's corner at H/40, a deeper and wider
// column). A column of 40 × 26 particles on Adami walls of 4 layers must settle without a growing
// wave for 0.05 s.
#include "Case.hpp"
#include "Log.hpp"
#include "Simulation.hpp"
#include "TestSupport.hpp"

#include <gtest/gtest.h>
#include <cmath>
#include <fstream>
#include <iostream>
#include <regex>
#include <utility>
#include <vector>

using namespace spindrift;
namespace fs = std::filesystem;

namespace {

// Replaces the first match of each pattern in 'file', in order.
void edit(const fs::path& file, const std::vector<std::pair<std::string, std::string>>& replacements) {
    std::string text = test::readFile(file);
    for (const auto& [pattern, by] : replacements)
        text = std::regex_replace(text, std::regex(pattern), by, std::regex_constants::format_first_only);
    std::ofstream(file) << text;
}

// The hydrostatic tank tutorial in 'dir' with 'solver', the Wendland C2 at a support of 4Δx of
// 'spacing' (0.0075: 26 × 40 particles; 0.015: 13 × 20), 4 wall layers, the tank 0.195 m wide.
void wideKernelTank(const fs::path& dir, const std::string& solver, const std::string& spacing) {
    copyCaseInput(fs::path(SPINDRIFT_SOURCE_DIR) / "tutorials/hydrostaticTank2D", dir);
    edit(dir / "system/sphSchemes",
         {{"\npressure\\s*\\{[^}]*\\}", "\npressure\n{\n    type " + solver + ";\n}"},
          {"(kernel\\s*\\{\\s*type\\s+)\\w+;", "$1wendlandC2;"},
          {"\nviscosity\\s*\\{[^}]*\\}", "\nviscosity\n{\n    type artificial; alpha 0.1; soundSpeed 25;\n}"}});
    edit(dir / "constant/fluidProperties",
         {{"supportRadius\\s+[^;]+;", "supportRadius 4;"}, {"particleSpacing\\s+[^;]+;", "particleSpacing " + spacing + ";"}});
    // whole numbers of either spacing: the tank 0.195 wide, its walls 0.405 high
    edit(dir / "constant/geometry",
         {{"layers\\s+3;", "layers 4;"}, {"\\(0\\.2 0\\.3 0\\)", "(0.195 0.3 0)"}, {"\\(0\\.2 0\\.4 0\\)", "(0.195 0.405 0)"}});
}

class JacobiRelaxation : public ::testing::TestWithParam<std::string> {};

TEST_P(JacobiRelaxation, AWideKernelSettlesAColumnWithoutAGrowingWave) {
    log::setQuiet(true);
    test::TempDir tmp;
    const fs::path dir = tmp.path() / "tank";
    wideKernelTank(dir, GetParam(), "0.0075");
    edit(dir / "system/controlDict", {{"\nendTime[^;]*;", "\nendTime 0.05;"}, {"\nwriteInterval[^;]*;", "\nwriteInterval 1;"}});

    Simulation sim(dir);
    const RunSummary r = sim.run(); // a blow-up throws
    EXPECT_GT(r.steps, 40);
    double vMax = 0;
    for (const auto& v : test::fluidOf(sim.scene()).particles.velocity()) vMax = std::max(vMax, double(v.norm()));
    // no wave grows: the start's settling at the corners stays far below the 0.5 m/s a free fall
    // reaches in 0.05 s (dfsph 0.14, pbf 0.12, iisph 0.01 m/s; a diverging iteration doubles the
    // speed every step)
    EXPECT_LT(vMax, 0.3) << GetParam();
    EXPECT_LT(r.maxDensityError, 0.01) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(EveryJacobiSolver, JacobiRelaxation, ::testing::Values("dfsph", "iisph", "pbf"),
                         [](const auto& info) { return info.param; });

// The bound holds on each solver's real gain (dfsph's and iisph's ω twice pcisph's δ, relaxedPbf's
// 1 + ω): held to it, a wide kernel's column (Wendland C2 at 4Δx, 13 × 20 particles) at a fixed
// number of iterations a step, with no stop criterion switching in between, stands still. Held
// in the nominal relaxation only, dfsph's and relaxedPbf's waves beyond the bound were clamped
// every step and the column rang for good: the bottom probe's std over 0.25–0.5 s 47 % (dfsph) and
// 30 % (relaxedPbf) of ρ0 g (H − z), period 20–30 steps (now 0.15 % and 0.05 %; pcisph, iisph, pbf
// 0.04 %, unchanged); the same mode swung the Colagrossi far wall at H/80 (issue 35).
class StillColumn : public ::testing::TestWithParam<std::string> {};

TEST_P(StillColumn, AtAFixedIterationCountAWideKernelsColumnStandsStill) {
    log::setQuiet(true);
    test::TempDir tmp;
    const fs::path dir = tmp.path() / "tank";
    wideKernelTank(dir, GetParam(), "0.015");
    // the bottom probe every step
    edit(dir / "system/controlDict",
         {{"\nendTime[^;]*;", "\nendTime 0.5;"},
          {"\nwriteInterval[^;]*;", "\nwriteInterval 1;\nfunctions { p { type probes; fields (pressure); "
                                    "probeLocations ((0.0975 0.045 0)); writeControl timeStep; writeInterval 1; } }"}});
    // four iterations a step, whatever the error (the stop criteria out of reach)
    std::ofstream(dir / "system/sphSolution") << "pressure { minIterations 4; maxDensityError 1; peakDensityError 1; }\n";

    Simulation sim(dir);
    const RunSummary r = sim.run();
    ASSERT_GT(r.steps, 300);
    const double exact = sim.scene().physics.rho0 * 9.81 * (0.3 - 0.045);
    double sum = 0, sum2 = 0;
    int samples = 0;
    for (const auto& row : test::readDataRows(dir / "postProcessing/p/0/p.dat")) {
        if (row.size() < 2 || row[0] < 0.25) continue; // after the start's settling
        sum += row[1], sum2 += row[1] * row[1];
        ++samples;
    }
    ASSERT_GT(samples, 100);
    const double mean = sum / samples, std = std::sqrt(std::max(0.0, sum2 / samples - mean * mean));
    std::cout << GetParam() << ": bottom probe over 0.25-0.5 s " << 100 * (mean / exact - 1) << " % of rho0 g (H - z), std "
              << 100 * std / exact << " %\n";
    EXPECT_LT(std / exact, 0.01) << GetParam();
    EXPECT_LT(std::abs(mean / exact - 1), 0.03) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(EveryJacobiSolver, StillColumn,
                         ::testing::Values("pcisph", "iisph", "dfsph", "pbf", "relaxedPbf"),
                         [](const auto& info) { return info.param; });

} // namespace
