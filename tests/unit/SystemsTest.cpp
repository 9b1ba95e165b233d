// Particle systems as peers (issue 37): a passive system added by a plugin is searched, looped,
// written and restarted by the core as it is (tracers carried by a uniform flow, to round-off);
// ghost particles are neighbours only (a periodic density from ghosts equals the minimum image's);
// the reactions of the pair terms give the force of the water on its tank (its weight, for every
// pressure solver) through the `forces` function object.
#include "Case.hpp"
#include "Log.hpp"
#include "PairLoop.hpp"
#include "Simulation.hpp"
#include "TestSupport.hpp"

#include <gtest/gtest.h>
#include <fstream>
#include <iostream>
#include <sstream>

using namespace spindrift;
namespace fs = std::filesystem;

namespace {

void write(const fs::path& file, const std::string& text) {
    fs::create_directories(file.parent_path());
    std::ofstream(file) << text;
}

std::string tracerLibrary() {
    return (fs::path(SPINDRIFT_TEMPLATE_PLUGIN_DIR) / pluginFileName("passive", "passiveTemplate")).string();
}

// Water moving at (1, 0.5) m/s through a box periodic in x and y, no walls, no gravity, with
// tracers (the passive template plugin, loaded from controlDict libs) seeded in its middle.
fs::path uniformFlowCase(const fs::path& dir, const std::string& endTime) {
    write(dir / "system/controlDict", "libs (\"" + tracerLibrary() + "\");\nendTime " + endTime +
                                          ";\ndeltaT 5e-4;\nwriteControl runTime;\nwriteInterval 0.01;\n");
    write(dir / "system/sphSchemes", "kernel { type wendlandC2; }\npressure { type wcsph; soundSpeed 20; }\n"
                                     "integrator { type symplecticEuler; }\n"
                                     "passive { tracers { type passiveTemplate; min (0.1 0.1 0); max (0.3 0.3 0); "
                                     "spacing 0.05; } }\n");
    write(dir / "constant/fluidProperties", "dimension 2;\nrho0 1000;\nparticleSpacing 0.02;\nsupportRadius 3;\n");
    write(dir / "constant/geometry", "fluid { water { type box; min (0 0 0); max (0.4 0.4 0); velocity (1 0.5 0); } }\n"
                                     "periodic { x (0 0.4); y (0 0.4); }\n");
    return dir;
}

TEST(Systems, APassiveSystemFromAPluginIsSearchedLoopedWrittenAndRestarted) {
    log::setQuiet(true);
    test::TempDir tmp;
    const fs::path whole = uniformFlowCase(tmp.path() / "whole", "0.04");
    {
        Simulation sim(whole);
        const ParticleSystem* tracers = sim.scene().find("tracers");
        ASSERT_NE(tracers, nullptr);
        EXPECT_EQ(tracers->role, SystemRole::passive);
        EXPECT_EQ(tracers->size(), 16u); // 4 × 4 on a spacing of 0.05
        sim.run();
    }
    // carried with the fluid's uniform velocity: displaced by v t, to round-off (wrapped)
    const ParticleSet start = readVtp(whole / "0/tracers.vtp"), end = readVtp(whole / "0.04/tracers.vtp");
    ASSERT_EQ(start.size(), 16u);
    ASSERT_EQ(end.size(), 16u);
    for (std::size_t i = 0; i < start.size(); ++i) {
        Vec3 expected = start.position()[i] + Vec3(0.04, 0.02, 0);
        EXPECT_LT((end.position()[i] - expected).norm(), test::tol(1e-9, 1e-5)) << "tracer " << i;
        EXPECT_LT((end.velocity()[i] - Vec3(1, 0.5, 0)).norm(), test::tol(1e-9, 1e-4)) << "tracer " << i;
    }
    // every written time has its block in the .pvd
    const std::string pvd = test::readFile(whole / "whole.pvd");
    for (const char* t : {"0", "0.01", "0.02", "0.03", "0.04"})
        EXPECT_NE(pvd.find(std::string("file=\"") + t + "/tracers.vtp\""), std::string::npos) << t;
    // a restart half way continues bit for bit, tracers included
    const fs::path split = uniformFlowCase(tmp.path() / "split", "0.02");
    Simulation(split).run();
    write(split / "system/controlDict", "libs (\"" + tracerLibrary() + "\");\nstartFrom latestTime;\nendTime 0.04;\n"
                                        "deltaT 5e-4;\nwriteControl runTime;\nwriteInterval 0.01;\n");
    Simulation(split).run();
    const ParticleSet a = readVtp(whole / "0.04/tracers.vtp"), b = readVtp(split / "0.04/tracers.vtp");
    EXPECT_EQ(a.position(), b.position());
    EXPECT_EQ(a.velocity(), b.velocity());
}

// The density of a lattice periodic in x, by the minimum image, and by ghost copies of the
// particles within a support of each end appended to a non-periodic system: the same for every
// particle of its own (the ghosts are neighbours only).
TEST(Systems, GhostParticlesAreNeighboursOnly) {
    const auto physics = test::physicsFor(2, 0.01, 3);
    auto kernel = test::createModel<Kernel>("type wendlandC2;", physics);
    const Scalar L = 0.2, h = test::constantsFor(physics).supportRadius;

    // the minimum image: the search over the periodic domain
    Scene fresh;
    fresh.physics = physics;
    ParticleSystem& f = test::fillLattice(fresh, *kernel, Vec3::Zero(), Vec3(L, 0.1, 0));
    Periodicity p;
    p.axis[0] = true;
    p.length = Vec3(L, 0, 0);
    fresh.search.setup(h, 2, Vec3(0, -0.1, 0), Vec3(L, 0.2, 0), p);
    fresh.registerWithSearch(f);
    fresh.search.build();
    std::vector<Scalar> rhoPeriodic;
    summationDensity(fresh, f, f.particles.position(), rhoPeriodic);
    {
        Scene ghosts;
        ghosts.physics = physics;
        ParticleSystem& g = test::fillLattice(ghosts, *kernel, Vec3::Zero(), Vec3(L, 0.1, 0));
        const std::size_t owned = g.size();
        for (std::size_t i = 0; i < owned; ++i) {
            const Vec3 x = g.particles.position()[i];
            if (x[0] < h) g.particles.append(x + Vec3(L, 0, 0), Vec3::Zero(), Index(i));
            if (x[0] > L - h) g.particles.append(x - Vec3(L, 0, 0), Vec3::Zero(), Index(i));
        }
        g.ghostCount = g.size() - owned;
        for (std::size_t i = owned; i < g.size(); ++i) g.particles.density()[i] = physics.rho0;
        ASSERT_GT(g.ghostCount, 0u);
        ghosts.search.setOwnedSize(g.index, owned);
        test::rebuild(ghosts);
        std::vector<Scalar> rhoGhosts;
        summationDensity(ghosts, g, g.particles.position(), rhoGhosts);
        ASSERT_EQ(ghosts.listsOf(g).size(), owned) << "rows for its own particles only";
        ASSERT_EQ(rhoPeriodic.size(), owned);
        for (std::size_t i = 0; i < owned; ++i)
            EXPECT_NEAR(rhoGhosts[i], rhoPeriodic[i], test::tol(1e-9, 1e-3)) << "particle " << i;
        // and the ends are not short of neighbours (the test is not vacuous)
        EXPECT_NEAR(rhoGhosts[0], rhoGhosts[10], test::tol(1e-9, 1e-3)); // the bottom row: x = 0.005 and 0.105
    }
}

// The hydrostaticTank2D tutorial with each pressure solver of damBreak2D's menu and a forces
// function object on the tank. Newton's third law, step by step: the impulse of the force the
// tank reports balances the water's momentum against its weight, P(2) − P(1) = −W·1 s − ∫F dt
// (the reactions are the forces the fluid felt, not a second model of them: to round-off for the
// force-based solvers, 3e-4 W·s for pbf and relaxedPbf, whose reaction is that of the pressure
// their position correction stands for); and once settled,
// the water presses on the tank with its weight on average (the iterative solvers' force is
// noisy from step to step: ±10–40 % of W, ±3 % over 0.1 s windows, so the average is over 1 s).
class TankForce : public testing::TestWithParam<std::string> {};

Eigen::Vector3d momentumOf(const ParticleSystem& water) {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (const Vec3& v : water.particles.velocity()) p += water.particles.particleMass() * v.cast<double>();
    return p;
}

TEST_P(TankForce, BalancesTheWaterMomentumAndIsItsWeight) {
    log::setQuiet(true);
    test::TempDir tmp;
    const fs::path dir = tmp.path() / "tank";
    copyCaseInput(fs::path(SPINDRIFT_SOURCE_DIR) / "tutorials/hydrostaticTank2D", dir);
    const std::string solver = GetParam();
    const auto setControl = [&](const std::string& startFrom, const std::string& endTime) {
        Dictionary control = Dictionary::fromFile(dir / "system/controlDict");
        control.set("startFrom", startFrom);
        control.set("endTime", endTime);
        control.set("writeInterval", "0.5");
        control.set("functions", "{ onTank { type forces; patches (tank); writeControl timeStep; writeInterval 1; } }");
        std::ofstream(dir / "system/controlDict") << control.toString();
    };
    {
        const Dictionary menu = Dictionary::fromFile(fs::path(SPINDRIFT_SOURCE_DIR) / "tutorials/damBreak2D/system/sphSchemes");
        Dictionary schemes = Dictionary::fromFile(dir / "system/sphSchemes");
        if (solver != "wcsph") {
            schemes.setDict("pressure", menu.subDict("pressureSolvers").subDict(solver));
            schemes.set("viscosity", "{ type laminar; }"); // (artificial needs a sound speed)
        }
        std::ofstream(dir / "system/sphSchemes") << schemes.toString();
    }
    setControl("startTime", "1.0");
    Eigen::Vector3d p1;
    {
        Simulation sim(dir);
        sim.run();
        p1 = momentumOf(*sim.scene().find("fluid"));
    }
    setControl("latestTime", "2.0");
    Simulation sim(dir);
    sim.run();
    const ParticleSystem& water = *sim.scene().find("fluid");
    const Eigen::Vector3d p2 = momentumOf(water);
    const double weight = 9.81 * water.particles.particleMass() * double(water.size());
    // force.dat of the restarted run: one row a step, the force of the step that ends at t
    const fs::path forceFile = dir / "postProcessing/onTank/1/force.dat";
    std::ifstream in(forceFile);
    std::string header, units;
    std::getline(in, header);
    EXPECT_EQ(header.rfind("# Time\ttotal_x\ttotal_y\ttotal_z\tpressure_x", 0), 0u) << header;
    std::getline(in, units);
    EXPECT_EQ(units.rfind("# [s]\t[N/m]\t[N/m]", 0), 0u) << "units: " << units;
    double impulse = 0, lastTime = 1.0, pressureSum = 0, sum = 0;
    int rows = 0;
    for (const auto& row : test::readDataRows(forceFile)) { // t, total x y z, pressure x y z
        ASSERT_GE(row.size(), 7u);
        impulse += row[2] * (row[0] - lastTime);
        lastTime = row[0];
        sum += row[2];
        pressureSum += row[5];
        ++rows;
    }
    ASSERT_GT(rows, 100);
    ASSERT_NEAR(lastTime, 2.0, 1e-9);
    const double balance = (p2 - p1).y() - (-weight * 1.0 - impulse);
    EXPECT_LT(std::abs(balance), 0.001 * weight) << solver << ": momentum change " << (p2 - p1).y() << " N s/m, weight "
                                                 << weight << " N/m, tank impulse " << impulse << " N s/m";
    const double fy = sum / rows;
    std::cout << solver << ": momentum balance " << balance / weight << " W s, mean force over 1–2 s " << -fy / weight
              << " W\n";
    EXPECT_NEAR(-fy / weight, 1.0, 0.015) << solver << ": force " << fy << " N/m, weight " << weight << " N/m";
    EXPECT_NEAR(pressureSum / rows, fy, 0.01 * weight) << "the pressure makes it";
}

INSTANTIATE_TEST_SUITE_P(EveryPressureSolver, TankForce,
                         testing::Values("wcsph", "pcisph", "iisph", "dfsph", "pbf", "relaxedPbf"));

} // namespace
