// dfsph (Bender & Koschier 2015): the density solve brings a compressed block to η and the
// step taken with its acceleration really decompresses it, momentum is conserved,
// checkPositions holds the real density after the step to η (also against a wall), the
// divergence solve removes a converging velocity field, a hydrostatic column (the
// hydrostaticTank2D tutorial run in-process) stays at rest near ρ0, and bad tolerances are
// refused.
#include "Case.hpp"
#include "Integrator.hpp"
#include "Log.hpp"
#include "Simulation.hpp"
#include "PairLoop.hpp"
#include "TestSupport.hpp"

#include <gtest/gtest.h>
#include <algorithm>
#include <fstream>
#include <regex>

using namespace spindrift;
namespace fs = std::filesystem;

namespace {

struct TestScene : test::BlockScene {
    explicit TestScene(int dim) : BlockScene(dim, "wendlandC2", 2.6) {}
    std::unique_ptr<PressureModel> pressure(const std::string& schemes, const std::string& solution) {
        return model<PressureModel>(schemes, solution);
    }
    // average positive Σ_j m (v_i − v_j)·∇W_ij over the particles with a full neighbourhood
    double compressionRate(const std::vector<Vec3>& v) const {
        const auto& ff = s.listsOf(test::fluidOf(s)).own();
        const auto& x = test::fluidOf(s).particles.position();
        double sum = 0;
        int count = 0;
        for (std::size_t i = 0; i < x.size(); ++i) {
            if (ff.count(i) < (s.physics.dimension == 3 ? 40u : 15u)) continue;
            double rate = 0;
            forEachNeighbour(ff, x, x, i, [&](Index j, const Vec3& rij, Scalar) {
                rate += test::fluidOf(s).particles.particleMass() * (v[i] - v[j]).dot(s.kernel.gradW(rij));
            });
            sum += std::max(rate, 0.0);
            ++count;
        }
        EXPECT_GT(count, 0);
        return sum / count;
    }
};

// The hydrostaticTank2D tutorial in tmp with dfsph (more pressure entries, e.g. "checkPositions
// yes;"), artificial viscosity, η = 0.1 % of the maximum, and the given end time, Courant
// number and largest Δt.
fs::path dfsphTank(const test::TempDir& tmp, const std::string& pressureEntries, double endTime, double maxCo,
                   double maxDeltaT) {
    const fs::path dir = tmp.path() / "tank";
    copyCaseInput(fs::path(SPINDRIFT_SOURCE_DIR) / "tutorials/hydrostaticTank2D", dir);
    std::string schemes = test::readFile(dir / "system/sphSchemes");
    schemes = std::regex_replace(schemes, std::regex("\npressure\\s*\\{[^}]*\\}"),
                                 "\npressure\n{\n    type dfsph; " + pressureEntries + "\n}",
                                 std::regex_constants::format_first_only);
    schemes = std::regex_replace(schemes, std::regex("\nviscosity\\s*\\{[^}]*\\}"),
                                 "\nviscosity\n{\n    type artificial; alpha 0.1; soundSpeed 25;\n}",
                                 std::regex_constants::format_first_only);
    std::ofstream(dir / "system/sphSchemes") << schemes;
    std::string control = test::readFile(dir / "system/controlDict");
    control = std::regex_replace(control, std::regex("\nendTime[^;]*;"), "\nendTime " + std::to_string(endTime) + ";");
    control = std::regex_replace(control, std::regex("\nwriteInterval[^;]*;"), "\nwriteInterval 1;");
    control = std::regex_replace(control, std::regex("\nmaxCo[^;]*;"), "\nmaxCo " + std::to_string(maxCo) + ";");
    control = std::regex_replace(control, std::regex("\nmaxDeltaT[^;]*;"), "\nmaxDeltaT " + std::to_string(maxDeltaT) + ";");
    std::ofstream(dir / "system/controlDict") << control;
    std::ofstream(dir / "system/sphSolution") << "pressure { maxDensityError 0.001; densityErrorNorm maximum; }\n";
    return dir;
}

TEST(Dfsph, DensitySolveReachesEtaAndTheStepDecompresses) {
    log::setQuiet(true);
    for (int dim : {2, 3}) {
        TestScene sc(dim);
        sc.block(dim == 2 ? 20 : 10, 0.99);
        const double eta = 1e-3, dt = 1e-3;
        auto p = sc.pressure("type dfsph; divergenceSolve no;",
                             "maxDensityError 0.001; densityErrorNorm maximum; minIterations 2; maxIterations 200;");
        EXPECT_TRUE(p->isIterative());
        p->computeDensity(sc.s, test::fluidOf(sc.s), test::stepOf(sc.s));
        const double before = sc.maxCompression();
        ASSERT_GT(before, 10 * eta);
        std::fill(test::fluidOf(sc.s).particles.acceleration().begin(), test::fluidOf(sc.s).particles.acceleration().end(), Vec3::Zero());
        p->addPressureAcceleration(sc.s, test::fluidOf(sc.s), test::stepOf(sc.s, dt));
        const SolverStats st = p->lastSolve();
        EXPECT_TRUE(st.converged) << dim << "D";
        EXPECT_GE(st.iterations, 2);
        EXPECT_LT(st.iterations, 200);
        EXPECT_LE(st.maxDensityError, eta);
        // pairwise antisymmetric: total momentum unchanged
        Vec3 total = Vec3::Zero();
        double scale = 0;
        for (const auto& a : test::fluidOf(sc.s).particles.acceleration()) {
            total += a;
            scale += a.norm();
        }
        EXPECT_GT(scale, 0);
        EXPECT_LT(total.norm(), test::tol(1e-10, 32 * test::eps) * scale); // float: ~30-term pair sums
        // the step with this acceleration: the real density falls
        sc.advance(*p, dt);
        const double after = sc.maxCompression();
        std::cout << dim << "D block compressed " << 100 * before << " %: " << st.iterations
                  << " iterations; predicted " << 100 * st.maxDensityError << " %, after the step " << 100 * after << " %\n";
        EXPECT_LT(after, 0.25 * before) << dim << "D";
    }
}

// The density solve holds the *predicted* density ρ + Δt Dρ/Dt to η; the real one at the
// positions the step leads to differs by O(Δt²). With checkPositions the solve goes on until
// the real density meets η too: a compressed block released in one long step.
TEST(Dfsph, CheckPositionsHoldsTheRealDensityToEta) {
    log::setQuiet(true);
    for (int dim : {2, 3}) {
        const double eta = 1e-3, dt = 2e-3;
        double real[2];
        for (int check : {0, 1}) {
            TestScene sc(dim);
            sc.block(dim == 2 ? 20 : 10, 0.97);
            auto p = sc.pressure(std::string("type dfsph; divergenceSolve no; checkPositions ") + (check ? "yes;" : "no;"),
                                 "maxDensityError 0.001; densityErrorNorm maximum; minIterations 2; maxIterations 500;");
            p->computeDensity(sc.s, test::fluidOf(sc.s), test::stepOf(sc.s));
            std::fill(test::fluidOf(sc.s).particles.acceleration().begin(), test::fluidOf(sc.s).particles.acceleration().end(), Vec3::Zero());
            p->addPressureAcceleration(sc.s, test::fluidOf(sc.s), test::stepOf(sc.s, dt));
            const SolverStats st = p->lastSolve();
            EXPECT_TRUE(st.converged) << dim << "D";
            EXPECT_LE(st.maxDensityError, eta);
            sc.advance(*p, dt);
            real[check] = sc.maxCompression();
            std::cout << dim << "D checkPositions " << check << ": " << st.iterations << " iterations, predicted "
                      << 100 * st.maxDensityError << " %, real after the step " << 100 * real[check] << " %\n";
        }
        EXPECT_GT(real[0], 2 * eta) << dim << "D: the linearisation error shows without the check";
        EXPECT_LE(real[1], 1.05 * eta) << dim << "D";
    }
}

// The same at a wall: a 3D block resting against a wall (three layers of wall particles
// continuing its lattice) driven into it at 0.15 h in one step. Wall particles it comes within
// h of in the step are not in the step's wall list; checkPositions searches at the predicted
// positions, so the real density after the step (summed afresh) meets η: 0.058 % (a check
// summing over the step's wall list alone left 0.150 %). (In 2D the same drive is too strong for the check: the solve
// stops at maxIterations with the real density 12 % over ρ0, with or without the walls found.)
TEST(Dfsph, CheckPositionsHoldsTheRealDensityToEtaAgainstAWall) {
    log::setQuiet(true);
    const int n = 10;
    const double eta = 1e-3, dt = 1e-3;
    TestScene sc(3);
    sc.block(n, 1.0);
    const double dx = sc.s.physics.particleSpacing, h = sc.s.constants.supportRadius;
    std::vector<Vec3> wall;
    for (int k = -3; k < n + 3; ++k)
        for (int j = -3; j < n + 3; ++j)
            for (int c = 1; c <= 3; ++c) wall.emplace_back(-(c - 0.5) * dx, (j + 0.5) * dx, (k + 0.5) * dx);
    test::addWallSystem(sc.s, "wall", wall);
    test::setWallMasses(sc.s, test::fluidOf(sc.s).particles.particleMass());
    test::rebuild(sc.s);
    for (auto& v : test::fluidOf(sc.s).particles.velocity()) v = Vec3(-0.15 * h / dt, 0, 0);
    auto p = sc.pressure("type dfsph; divergenceSolve no; checkPositions yes;",
                         "maxDensityError 0.001; densityErrorNorm maximum; minIterations 2; maxIterations 500;");
    p->computeDensity(sc.s, test::fluidOf(sc.s), test::stepOf(sc.s));
    const double before = sc.maxCompression();
    std::fill(test::fluidOf(sc.s).particles.acceleration().begin(), test::fluidOf(sc.s).particles.acceleration().end(), Vec3::Zero());
    p->addPressureAcceleration(sc.s, test::fluidOf(sc.s), test::stepOf(sc.s, dt));
    const SolverStats st = p->lastSolve();
    EXPECT_TRUE(st.converged);
    EXPECT_LE(before, eta);
    sc.advance(*p, dt);
    const double after = sc.maxCompression();
    std::cout << "block driven into a wall at 0.15 h a step: " << st.iterations << " iterations; real density "
              << 100 * after << " % over rho0 after the step\n";
    EXPECT_LE(after, 1.01 * eta);
}

// A check that passes has searched at the positions the step leads to: once the integrator
// (symplectic Euler) has taken the step, the next evaluation takes that search and density
// instead of searching again, and they equal a fresh search and density bit for bit; also
// when the particles are re-sorted in between, as the time loop does every few steps
// (resortFluid: the lists relabelled, the cached gradients and the model's scratch fields
// reordered).
TEST(Dfsph, APassedCheckLeavesTheNextSearchAndDensity) {
    log::setQuiet(true);
    for (int dim : {2, 3})
        for (bool resort : {false, true}) {
            const double eta = 1e-3, dt = 2e-3;
            const std::string schemes = "type dfsph; divergenceSolve no; checkPositions yes;";
            const std::string solution = "maxDensityError 0.001; densityErrorNorm maximum; minIterations 2; maxIterations 500;";
            TestScene sc(dim);
            sc.block(dim == 2 ? 20 : 10, 0.97);
            auto& s = sc.s;
            auto p = sc.pressure(schemes, solution);
            auto integrator = test::createModel<Integrator>("type symplecticEuler;", s.physics);
            p->computeDensity(s, test::fluidOf(s), test::stepOf(s));
            EXPECT_FALSE(s.search.builtAt(test::fluidOf(s).index, test::fluidOf(s).particles.position()));
            std::fill(test::fluidOf(s).particles.acceleration().begin(), test::fluidOf(s).particles.acceleration().end(), Vec3::Zero());
            p->addPressureAcceleration(s, test::fluidOf(s), test::stepOf(s, dt));
            ASSERT_TRUE(p->lastSolve().converged) << dim << "D";
            integrator->step(s, test::noServices(), Scalar(dt), [](double, Scalar) {}); // with the acceleration just computed
            ASSERT_TRUE(s.search.builtAt(test::fluidOf(s).index, test::fluidOf(s).particles.position())) << dim << "D: the integrator's positions are not the checked ones";
            const long builds = s.search.builds();
            if (resort) { // as Simulation::run
                const std::vector<Index> order = s.search.sortOrder(test::fluidOf(s).particles.position());
                ASSERT_FALSE(std::is_sorted(order.begin(), order.end())) << "the re-sort must move particles";
                resortSystem(s, test::fluidOf(s));
                ASSERT_TRUE(s.search.builtAt(test::fluidOf(s).index, test::fluidOf(s).particles.position())) << dim << "D after the re-sort";
            }

            const NeighbourList taken = s.listsOf(test::fluidOf(s)).own();
            p->computeDensity(s, test::fluidOf(s), test::stepOf(s));
            EXPECT_EQ(s.search.builds(), builds); // no search of its own
            const std::vector<Scalar> density = test::fluidOf(s).particles.density();
            ASSERT_TRUE(test::fluidOf(s).gradients.validFor(s.listsOf(test::fluidOf(s))));
            const std::vector<Vec3> gradients = test::fluidOf(s).gradients.values;

            test::rebuild(s);
            auto fresh = sc.pressure(schemes, solution);
            fresh->computeDensity(s, test::fluidOf(s), test::stepOf(s));
            EXPECT_EQ(taken.offsets, s.listsOf(test::fluidOf(s)).own().offsets);
            EXPECT_EQ(taken.indices, s.listsOf(test::fluidOf(s)).own().indices);
            EXPECT_EQ(density, test::fluidOf(s).particles.density()) << dim << "D, re-sort " << resort;
            EXPECT_EQ(gradients, test::fluidOf(s).gradients.values) << dim << "D, re-sort " << resort;
            std::cout << dim << "D" << (resort ? ", re-sorted" : "") << ": real density after the step "
                      << 100 * sc.maxCompression() << " % over rho0\n";
            EXPECT_LE(sc.maxCompression(), eta * (1 + test::tol(1e-9, 1e-4))); // float: ρ's rounding
        }
}

// The same in a run: hydrostaticTank2D with dfsph, checkPositions and symplectic Euler. Without
// the check a step searches once; with it, a step whose check passed takes that search (also
// over a re-sort), so only the steps whose check failed search more.
TEST(Dfsph, ARunSearchesOnceAStepWithTheCheck) {
    log::setQuiet(true);
    for (const char* check : {"no", "yes"}) {
        test::TempDir tmp;
        const fs::path dir = dfsphTank(tmp, std::string("checkPositions ") + check + ";", 0.1, 0.15, 1e-3);
        Simulation sim(dir);
        const long before = sim.scene().search.builds();
        const RunSummary r = sim.run();
        const long searches = sim.scene().search.builds() - before;
        std::cout << "checkPositions " << check << ": " << r.steps << " steps, " << searches
                  << " neighbour searches, real density error at most " << 100 * r.maxDensityError << " %\n";
        ASSERT_GT(r.steps, 50);
        if (check[0] == 'n') {
            EXPECT_EQ(searches, r.steps); // one a step (the first takes the start time's)
        } else {
            EXPECT_LE(searches, r.steps + 1 + r.steps / 5); // without taking the check's: twice a step
            EXPECT_LE(r.maxDensityError, 0.001 * (1 + test::tol(1e-9, 1e-4)));
        }
    }
}

TEST(Dfsph, DivergenceSolveRemovesAConvergingVelocityField) {
    log::setQuiet(true);
    for (int dim : {2, 3}) {
        TestScene sc(dim);
        const Vec3 c = sc.block(dim == 2 ? 20 : 10, 1.0);
        auto& v = test::fluidOf(sc.s).particles.velocity();
        for (std::size_t i = 0; i < v.size(); ++i) v[i] = -0.5 * (test::fluidOf(sc.s).particles.position()[i] - c); // converging
        const double dt = 1e-3;
        const double before = sc.compressionRate(v);
        ASSERT_GT(before, 0);
        std::vector<double> residual;
        for (const char* divergence : {"no", "yes"}) {
            auto p = sc.pressure(std::string("type dfsph; warmStart 0; divergenceSolve ") + divergence + ";",
                                 "maxDensityError 1; minIterations 0; maxDivergenceError 1e-6; maxDivergenceIterations 500;");
            p->computeDensity(sc.s, test::fluidOf(sc.s), test::stepOf(sc.s));
            std::fill(test::fluidOf(sc.s).particles.acceleration().begin(), test::fluidOf(sc.s).particles.acceleration().end(), Vec3::Zero());
            p->addPressureAcceleration(sc.s, test::fluidOf(sc.s), test::stepOf(sc.s, dt));
            std::vector<Vec3> next(v.size());
            for (std::size_t i = 0; i < v.size(); ++i) next[i] = v[i] + dt * test::fluidOf(sc.s).particles.acceleration()[i];
            residual.push_back(sc.compressionRate(next));
        }
        std::cout << dim << "D: compression rate " << before << " -> " << residual[0] << " (density solve only, at η = 100 %: "
                  << "no correction) -> " << residual[1] << " (with the divergence solve)\n";
        EXPECT_NEAR(residual[0], before, 1e-9 * before); // nothing acts without the divergence solve
        EXPECT_LT(residual[1], 0.05 * before) << dim << "D";
    }
}

TEST(Dfsph, RejectsBadSettings) {
    log::setQuiet(true);
    TestScene sc(2);
    sc.block(6, 1.0);
    EXPECT_THROW(sc.pressure("type dfsph; warmStart 2;", ""), InputError);
    EXPECT_THROW(sc.pressure("type dfsph;", "maxDivergenceIterations 0;"), InputError);
    EXPECT_THROW(sc.pressure("type dfsph;", "maxDivergenceError -1;"), InputError);
    EXPECT_THROW(sc.pressure("type dfsph;", "maxDivergenceErorr 0.01;"), InputError); // typo
    EXPECT_THROW(sc.pressure("type dfsph; divergenceSolv no;", ""), InputError);       // typo
}

// hydrostaticTank2D with dfsph and an adjustable time step: at rest near ρ0 after 1 s
TEST(Dfsph, KeepsAHydrostaticColumnAtRest) {
    log::setQuiet(true);
    test::TempDir tmp;
    const fs::path dir = dfsphTank(tmp, "", 1, 0.3, 2e-3);
    Simulation sim(dir);
    const RunSummary r = sim.run();
    EXPECT_GT(r.steps, 300);
    auto& s = sim.scene();
    sim.evaluate(sim.scene().time, Scalar(2e-3));
    const double rho0 = s.physics.rho0;
    double maxErr = 0, vMax = 0, v2 = 0, pBottom = 0;
    int nBottom = 0;
    for (std::size_t i = 0; i < test::fluidOf(s).particles.size(); ++i) {
        const Vec3 x = test::fluidOf(s).particles.position()[i];
        ASSERT_GE(x.y(), 0.0);
        maxErr = std::max(maxErr, (test::fluidOf(s).particles.density()[i] - rho0) / rho0);
        vMax = std::max(vMax, double(test::fluidOf(s).particles.velocity()[i].norm()));
        v2 += test::fluidOf(s).particles.velocity()[i].squaredNorm();
        if (x.y() < s.physics.particleSpacing) {
            pBottom += test::fluidOf(s).particles.pressure()[i];
            ++nBottom;
        }
    }
    std::cout << "dfsph hydrostatic column: " << r.steps << " steps, " << r.averageIterations
              << " iterations on average; final max density error " << 100 * maxErr << " %, max speed " << vMax
              << " m/s, RMS speed " << std::sqrt(v2 / test::fluidOf(s).particles.size()) << " m/s, bottom pressure " << pBottom / nBottom << " Pa (rho0 g H = " << rho0 * 9.81 * 0.3 << " Pa)\n";
    EXPECT_LE(maxErr, 0.01);
    // at rest
    EXPECT_LT(std::sqrt(v2 / test::fluidOf(s).particles.size()), 0.01);
    EXPECT_LT(vMax, 0.1);
    // p = ρκ carries the column. One solve's κ fluctuates from step to step by ±25 % (the solves
    // stop at η and warm-start from half of the last κ), so the pressure is averaged over 50
    // more steps (symplectic Euler, Δt = 2 ms) in the centre column, away from the side walls:
    // its slope between 0.05 and 0.25 m height is ρ0 g within 15 %, and the mid-depth row
    // within 20 % of ρ0 g (H − z). Next to a wall p is about twice that (the plugin's header).
    const Scalar dt = Scalar(2e-3);
    const int samples = 50;
    double sy = 0, sp = 0, syy = 0, syp = 0, pMid = 0;
    long nFit = 0, nMid = 0;
    for (int step = 0; step < samples; ++step) {
        auto& x = test::fluidOf(s).particles.position();
        auto& v = test::fluidOf(s).particles.velocity();
        for (std::size_t i = 0; i < test::fluidOf(s).particles.size(); ++i) {
            v[i] += dt * test::fluidOf(s).particles.acceleration()[i];
            x[i] += dt * v[i];
        }
        sim.evaluate(sim.scene().time, dt);
        for (std::size_t i = 0; i < test::fluidOf(s).particles.size(); ++i) {
            const double y = x[i].y(), p = test::fluidOf(s).particles.pressure()[i];
            if (x[i].x() < 0.05 || x[i].x() > 0.15) continue;
            if (y > 0.05 && y < 0.25) {
                sy += y, sp += p, syy += y * y, syp += y * p;
                ++nFit;
            }
            if (std::abs(y - 0.15) < 0.005) {
                pMid += p;
                ++nMid;
            }
        }
    }
    ASSERT_GT(nMid, 0);
    const double slope = (nFit * syp - sy * sp) / (nFit * syy - sy * sy);
    pMid /= nMid;
    std::cout << "time-averaged pressure: dp/dy " << slope << " Pa/m (-rho0 g = " << -rho0 * 9.81 << "), mid-depth "
              << pMid << " Pa vs " << rho0 * 9.81 * 0.15 << " Pa\n";
    EXPECT_NEAR(slope, -rho0 * 9.81, 0.15 * rho0 * 9.81);
    EXPECT_NEAR(pMid, rho0 * 9.81 * 0.15, 0.2 * rho0 * 9.81 * 0.15);
}

} // namespace
