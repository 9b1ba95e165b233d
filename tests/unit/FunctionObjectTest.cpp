// Function-object plugins (probes, surgeFront, waterLevel, fieldStats, solverPerformance) on
// small lattices: values against hand computations, their output files and sampling control.
#include "TestSupport.hpp"
#include "PostProcess.hpp"

#include <gtest/gtest.h>
#include <cmath>
#include <fstream>
#include <sstream>

using namespace spindrift;
namespace fs = std::filesystem;

namespace {

// A block of fluid on a lattice of spacing dx = 0.01 in [0, nx dx) × [0, ny dx) (2D).
struct TestScene {
    Scene s;
    std::unique_ptr<Kernel> kernel;
    test::TempDir dir{"spindrift-fo-test"};
    std::vector<std::unique_ptr<Dictionary>> dicts;

    TestScene(int nx, int ny, Vec3 gravity = Vec3(0, -9.81, 0)) {
        s.physics = test::physicsFor(2, 0.01, 2.6);
        s.physics.gravity = gravity;
        kernel = test::createModel<Kernel>("type wendlandC2;", s.physics);
        test::fillLattice(s, *kernel, Vec3::Zero(), Vec3(nx * 0.01, ny * 0.01, 0));
    }
    std::unique_ptr<FunctionObject> create(const std::string& name, const std::string& text) {
        dicts.push_back(std::make_unique<Dictionary>(Dictionary::fromString(text, "controlDict.functions." + name)));
        return ModelRegistry::instance().create<FunctionObject>(*dicts.back(), s.physics, s.constants, nullptr, dir.path(), name);
    }
    // rows of postProcessing/<name>/0/<file>.dat; the header's column names and units lines
    std::vector<std::vector<double>> rows(const std::string& name, std::string* header = nullptr,
                                          const std::string& file = "", std::string* units = nullptr) const {
        const fs::path path = dir.path() / "postProcessing" / name / "0" / ((file.empty() ? name : file) + ".dat");
        std::ifstream in(path);
        std::string line;
        while (std::getline(in, line) && !line.empty() && line[0] == '#') {
            if (header && header->empty()) *header = line;
            else if (units && units->empty()) *units = line;
        }
        return test::readDataRows(path);
    }
};

TEST(Probes, ShepardInterpolationIsExactForConstantsAndAccurateForLinearFields) {
    TestScene sc(20, 20, Vec3::Zero());
    auto& x = test::fluidOf(sc.s).particles.position();
    for (std::size_t i = 0; i < x.size(); ++i) {
        test::fluidOf(sc.s).particles.pressure()[i] = 1000 + 500 * x[i][0] - 300 * x[i][1]; // linear
        test::fluidOf(sc.s).particles.velocity()[i] = Vec3(2, -1, 0);                          // constant
    }
    auto probes = sc.create("p", "type probes; fields (pressure velocity density); "
                                 "probeLocations ((0.1037 0.0871 0) (0.0049 0.1 0) (1 1 0));");
    probes->start(sc.s, 0);
    sc.s.time = 0.001;
    probes->execute(sc.s, false);
    std::string header, units;
    const auto rows = sc.rows("p", &header, "", &units);
    ASSERT_EQ(rows.size(), 2u); // the start row and one sample, of the same state
    for (std::size_t k = 1; k < rows[0].size(); ++k) {
        if (!std::isnan(rows[0][k])) {
            EXPECT_EQ(rows[0][k], rows[1][k]) << k;
        }
    }
    const std::vector<std::vector<double>> r{rows[1]};
    // Time, p × 3, (Ux Uy) × 3, rho × 3
    ASSERT_EQ(r[0].size(), 1u + 3 + 6 + 3);
    EXPECT_NE(header.find("p(0.1037,0.0871)"), std::string::npos) << header;
    EXPECT_NE(header.find("Uy(0.0049,0.1)"), std::string::npos) << header;
    EXPECT_EQ(units, "# [s]\t[Pa]\t[Pa]\t[Pa]\t[m/s]\t[m/s]\t[m/s]\t[m/s]\t[m/s]\t[m/s]\t[kg/m^3]\t[kg/m^3]\t[kg/m^3]");
    // interior: a linear field within 2 % of its change over one spacing (the lattice's
    // kernel first moment at an off-lattice point), constants to round-off
    EXPECT_NEAR(r[0][1], 1000 + 500 * 0.1037 - 300 * 0.0871, 0.02 * 0.01 * std::hypot(500.0, 300.0));
    EXPECT_NEAR(r[0][4], 2.0, 1e-12);
    EXPECT_NEAR(r[0][5], -1.0, 1e-12);
    EXPECT_NEAR(r[0][10], 1000.0, test::tol(1e-9, 4 * test::eps * 1000)); // float: a few ulps
    // at the block's edge (half the support outside the fluid) Shepard still returns constants
    EXPECT_NEAR(r[0][6], 2.0, 1e-12);
    EXPECT_NEAR(r[0][7], -1.0, 1e-12);
    // no fluid within the support: nan
    EXPECT_TRUE(std::isnan(r[0][3]));
    EXPECT_TRUE(std::isnan(r[0][8]));
}

TEST(Probes, ALocationOutsideTheCaseIsWarnedOfOnceAtSetUpAndSamplesNan) {
    TestScene sc(10, 10); // fluid particles in [0, 0.1]², support radius 0.026
    // inside; 0.4 m above the block (a length in the wrong units); above the block but within
    // the support of its top row (a gauge over the free surface: no warning)
    auto probes = sc.create("p", "type probes; fields (pressure);\n"
                                 "probeLocations ((0.05 0.05 0) (0.05 0.5 0) (0.05 0.11 0));");
    testing::internal::CaptureStdout();
    probes->start(sc.s, 0);
    const std::string setUp = testing::internal::GetCapturedStdout();
    EXPECT_NE(setUp.find("--> Warning: controlDict.functions.p:2:1: probes 'p': location (0.05 0.5) lies outside "
                         "the case"),
              std::string::npos)
        << setUp;
    EXPECT_NE(setUp.find("(keyword 'probeLocations')"), std::string::npos) << setUp;
    EXPECT_EQ(setUp.find("(0.05 0.11)"), std::string::npos) << setUp;
    EXPECT_EQ(setUp.find("(0.05 0.05)"), std::string::npos) << setUp;
    testing::internal::CaptureStdout();
    for (double t : {0.001, 0.002}) {
        sc.s.time = t;
        probes->execute(sc.s, false);
    }
    EXPECT_EQ(testing::internal::GetCapturedStdout().find("arning"), std::string::npos) << "warned once, at set-up";
    const auto r = sc.rows("p");
    ASSERT_EQ(r.size(), 3u); // start row + two samples
    for (const auto& row : r) {
        ASSERT_EQ(row.size(), 4u); // the column is kept (the layout follows probeLocations)
        EXPECT_TRUE(std::isfinite(row[1]));
        EXPECT_TRUE(std::isnan(row[2]));
        EXPECT_TRUE(std::isfinite(row[3]));
    }
}

TEST(Probes, UnknownFieldIsAnInputErrorNamingTheCaseFields) {
    TestScene sc(5, 5);
    auto probes = sc.create("p", "type probes; fields (pressure vorticity); probeLocations ((0 0 0));");
    try {
        probes->start(sc.s, 0);
        FAIL() << "an unknown field must be an error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("vorticity"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("density"), std::string::npos) << e.what();
        EXPECT_EQ(e.keyword(), "fields");
    }
}

TEST(SurgeFront, FurthestParticleNearTheFloorWithEnoughNeighbours) {
    TestScene sc(10, 20); // x < 0.1, y < 0.2
    auto& x = test::fluidOf(sc.s).particles.position();
    // a particle of the top row moved far ahead (above the floor band), and an isolated drop on
    // the floor further still
    x[x.size() - 1] = Vec3(0.3, 0.15, 0);
    x[0] = Vec3(0.5, 0.005, 0);
    test::rebuild(sc.s);
    auto all = sc.create("all", "type surgeFront;");
    auto floor = sc.create("floor", "type surgeFront; maxHeight 0.02; minNeighbours 3;");
    all->start(sc.s, 0);
    floor->start(sc.s, 0);
    sc.s.time = 0.01;
    all->execute(sc.s, false);
    floor->execute(sc.s, false);
    const auto a = sc.rows("all"), f = sc.rows("floor");
    ASSERT_EQ(a.size(), 2u); // start row + one sample
    EXPECT_NEAR(a[1][1], 0.5, 1e-12);
    // the drop has no neighbour and the moved particle is above the band: the block's edge
    // (float: to the rounding of a position of size 0.1)
    const double xTol = test::tol(1e-12, 0.1 * test::eps);
    EXPECT_NEAR(f[1][1], 0.095, xTol);
    EXPECT_NEAR(f[1][2], 0.095, xTol);
    EXPECT_LT(f[1][3], 0.02);
}

TEST(WaterLevel, FindsTheFreeSurfaceOfALatticeBlockAndTheBaseWhenDry) {
    TestScene sc(20, 30); // surface at H = 0.3, width 0.2
    auto level = sc.create("level", "type waterLevel; gaugeLocations ((0.1 0 0) (0.5 0 0)); writeControl timeStep;");
    level->start(sc.s, 0);
    const auto r = sc.rows("level");
    ASSERT_EQ(r.size(), 1u);
    // continuum: φ = ½ exactly at a flat surface; on the lattice within a quarter spacing
    EXPECT_NEAR(r[0][1], 0.3, 0.25 * 0.01);
    EXPECT_DOUBLE_EQ(r[0][2], 0.0); // dry gauge: its own height
}

TEST(WaterLevel, NeedsGravity) {
    TestScene sc(5, 5, Vec3::Zero());
    EXPECT_THROW(sc.create("level", "type waterLevel; gaugeLocations ((0 0 0));"), InputError);
}

TEST(FieldStats, EnergyMomentumDensityErrorSpacingAndBounds) {
    TestScene sc(10, 10, Vec3::Zero());
    auto& s = sc.s;
    const double m = test::fluidOf(s).particles.particleMass();
    double ke = 0, px = 0, py = 0, vmax = 0;
    for (std::size_t i = 0; i < test::fluidOf(s).particles.size(); ++i) {
        const Vec3 v(0.1 * double(i % 7), -0.05 * double(i % 3), 0);
        test::fluidOf(s).particles.velocity()[i] = v;
        test::fluidOf(s).particles.density()[i] = 1000 * (1 + 0.001 * (double(i % 5) - 2)); // errors -0.2 % .. +0.2 %
        ke += 0.5 * m * v.squaredNorm();
        px += m * v.x();
        py += m * v.y();
        vmax = std::max(vmax, double(v.norm()));
    }
    auto stats = sc.create("stats", "type fieldStats;");
    stats->start(s, 0);
    std::string header, units;
    const auto r = sc.rows("stats", &header, "", &units);
    ASSERT_EQ(r.size(), 1u);
    EXPECT_NE(header.find("kineticEnergy"), std::string::npos);
    // the units of every column (2D: per metre of depth), the density error in %
    EXPECT_EQ(units, "# [s]\t[-]\t[%]\t[%]\t[%]\t[J/m]\t[kg/s]\t[kg/s]\t[m/s]\t[m]\t[m]\t[m]\t[m]\t[m]");
    // Time nParticles rhoErrMin rhoErrMax rhoErrAvg kineticEnergy momentumX momentumY maxSpeed
    // minPairDistance xMin xMax yMin yMax
    ASSERT_EQ(r[0].size(), 14u);
    EXPECT_EQ(r[0][1], 100);
    // the density error (ρ − ρ0)/ρ0 in %, as the log's step line
    EXPECT_NEAR(r[0][2], -0.2, 1e-10);
    EXPECT_NEAR(r[0][3], 0.2, 1e-10);
    EXPECT_NEAR(r[0][4], 0.0, 1e-10); // i % 5 is balanced over 100 particles
    EXPECT_NEAR(r[0][5], ke, 1e-9 * ke); // written with 10 digits
    EXPECT_NEAR(r[0][6], px, 1e-9 * std::abs(px));
    EXPECT_NEAR(r[0][7], py, 1e-9 * std::abs(py));
    EXPECT_NEAR(r[0][8], vmax, test::tol(1e-9, 4 * test::eps) * vmax); // float: |v| in Scalar
    // float: to the rounding of positions of size 0.1
    const double xTol = test::tol(1e-12, 0.1 * test::eps);
    EXPECT_NEAR(r[0][9], 0.01, xTol); // lattice spacing
    EXPECT_NEAR(r[0][10], 0.005, xTol);
    EXPECT_NEAR(r[0][11], 0.095, xTol);
    // after a step: the closest pair from the neighbour lists
    test::fluidOf(s).particles.position()[0] = Vec3(0.012, 0.005, 0); // 0.003 from its neighbour at (0.015, 0.005)
    test::rebuild(s);
    stats->execute(s, false);
    const auto r2 = sc.rows("stats");
    ASSERT_EQ(r2.size(), 2u);
    EXPECT_NEAR(r2[1][9], 0.003, xTol);
}

TEST(FieldStats, RunTimeSamplingWritesOneRowPerInterval) {
    TestScene sc(4, 4, Vec3::Zero());
    auto stats = sc.create("stats", "type fieldStats; writeControl runTime; writeInterval 0.1;");
    auto every3 = sc.create("every3", "type fieldStats; writeInterval 3;");
    stats->start(sc.s, 0);
    every3->start(sc.s, 0);
    for (int step = 1; step <= 24; ++step) { // Δt = 0.013: crosses 0.1, 0.2 and 0.3
        sc.s.time = 0.013 * step;
        stats->execute(sc.s, false);
        every3->execute(sc.s, false);
    }
    const auto r = sc.rows("stats");
    ASSERT_EQ(r.size(), 4u); // start + 3 samples
    EXPECT_NEAR(r[1][0], 0.013 * 8, 1e-12);
    EXPECT_NEAR(r[2][0], 0.013 * 16, 1e-12);
    EXPECT_NEAR(r[3][0], 0.013 * 24, 1e-12);
    EXPECT_EQ(sc.rows("every3").size(), 1u + 24 / 3);
}

TEST(SolverPerformance, SummarisesTheCoreRows) {
    TestScene sc(4, 4, Vec3::Zero());
    const fs::path core = sc.dir.path() / "postProcessing" / "solverPerformance" / "0";
    fs::create_directories(core);
    const std::string coreRows = "# Time\titerations\tconverged\tmaxDensityError\tavgDensityError\n"
                                 "0.1\t4\t1\t0.01\t0.002\n0.2\t6\t1\t0.008\t0.004\n0.3\t20\t0\t0.03\t0.006\n";
    std::ofstream(core / "solverPerformance.dat") << coreRows;
    auto perf = sc.create("solverPerformance", "type solverPerformance;");
    perf->start(sc.s, 0);
    sc.s.time = 0.3;
    perf->end(sc.s);
    const auto r = sc.rows("solverPerformance", nullptr, "solverPerformanceSummary");
    ASSERT_EQ(r.size(), 1u);
    // Time steps averageIterations maxIterations notConverged maxDensityError averageDensityError
    EXPECT_EQ(r[0][1], 3);
    EXPECT_NEAR(r[0][2], 10.0, 1e-12);
    EXPECT_EQ(r[0][3], 20);
    EXPECT_EQ(r[0][4], 1);
    EXPECT_NEAR(r[0][5], 0.03, 1e-12);
    EXPECT_NEAR(r[0][6], 0.004, 1e-12);
    // the core's file is untouched
    EXPECT_EQ(test::readFile(core / "solverPerformance.dat"), coreRows);
}

TEST(FunctionObjects, UnknownKeywordIsAnError) {
    TestScene sc(4, 4);
    EXPECT_THROW(sc.create("stats", "type fieldStats; writeIntervall 3;"), InputError);
}

} // namespace

TEST(PostProcess, SelectTimesTakesTimesRangesAndLatestTime) {
    const std::vector<std::pair<double, std::string>> written{
        {0, "0"}, {0.01, "0.01"}, {0.02, "0.02"}, {0.03, "0.03"}, {1e-05 * 4000, "0.04"}};
    const auto names = [&](const std::string& selection) {
        std::string s;
        for (const auto& t : selectTimes(written, selection)) s += (s.empty() ? "" : " ") + t.second;
        return s;
    };
    EXPECT_EQ(names(""), "0 0.01 0.02 0.03 0.04");
    EXPECT_EQ(names("0.02"), "0.02");
    EXPECT_EQ(names("0.01, 0.03"), "0.01 0.03");
    EXPECT_EQ(names("0.015:0.03"), "0.02 0.03"); // inclusive
    EXPECT_EQ(names(":0.01"), "0 0.01");
    EXPECT_EQ(names("0.03:"), "0.03 0.04");
    EXPECT_EQ(names("latestTime"), "0.04");
    EXPECT_EQ(names("0.04000000001"), "0.04");  // within 1e-9 (relative)
    EXPECT_EQ(names("0.5"), "");                // nothing: postProcess() names the written times
    EXPECT_EQ(names("0,0:0.01"), "0 0.01");     // each once, in time order
    for (const char* bad : {"a", "0.1:b", "0.1:0.2:0.3", "0.1,,x"})
        EXPECT_THROW(selectTimes(written, bad), std::runtime_error) << bad;
}
