// pcisph (Solenthaler & Pajarola 2009): the pressure scaling δ against a hand computation on
// 2D and 3D lattices, convergence to the maximum density error η with the returned
// acceleration realising the verified prediction, the maxIterations stop, the lattice
// correction gain that scales δ for wide supports, a hydrostatic column kept within η of ρ0
// (the hydrostaticTank2D tutorial run in-process) and the speed benchmark's dam break at 2 ms.
#include "Case.hpp"
#include "../../plugins/pressure/common/LatticePrototype.hpp"
#include "Log.hpp"
#include "Simulation.hpp"
#include "PairLoop.hpp"
#include "TestSupport.hpp"

#include <gtest/gtest.h>
#include <cmath>
#include <fstream>
#include <limits>
#include <regex>

using namespace spindrift;
namespace fs = std::filesystem;

namespace {

// Analytic dW/dr of the cubic spline (docs/MODELS.md §cubicSpline: σ(6q³ − 6q² + 1), 2σ(1 − q)³), written
// out here independently of the plugin.
double cubicSplineDW(double r, double h, int dim) {
    const double sigma = dim == 2 ? 40.0 / (7.0 * M_PI * h * h) : 8.0 / (M_PI * h * h * h);
    const double q = r / h;
    if (q >= 1) return 0;
    if (q <= 0.5) return sigma * (18 * q * q - 12 * q) / h;
    return -6 * sigma * (1 - q) * (1 - q) / h;
}

struct Scene : test::BlockScene {
    Scene(int dim, const std::string& kernelName, double supportFactor) : BlockScene(dim, kernelName, supportFactor) {}
    std::unique_ptr<PressureModel> pressure(const std::string& schemes, const std::string& solution) {
        return model<PressureModel>(schemes, solution);
    }
    // particles at least 'layers' spacings inside the block (a full neighbourhood)
    std::vector<std::size_t> interior(int n, int layers) const {
        std::vector<std::size_t> ids;
        const double dx = s.physics.particleSpacing;
        const Vec3 c(0.5 * n * dx, 0.5 * n * dx, s.physics.dimension == 3 ? 0.5 * n * dx : 0);
        const double half = (0.5 * n - layers) * dx;
        for (std::size_t i = 0; i < test::fluidOf(s).particles.size(); ++i) {
            const Vec3 d = (test::fluidOf(s).particles.position()[i] - c).cwiseAbs();
            if (d.maxCoeff() < half) ids.push_back(i);
        }
        return ids;
    }
};

TEST(Pcisph, DeltaMatchesHandComputationOn2DAnd3DLattices) {
    log::setQuiet(true);
    for (int dim : {2, 3}) {
        // support 1.5 Δx: the prototype's neighbours are the 4 (2D) or 6 (3D) at Δx and the
        // 4 (2D) or 12 (3D) at √2 Δx; Σ∇W = 0 by symmetry, so δ = ρ0² / (2 Δt² m² Σ W'(r)²).
        Scene sc(dim, "cubicSpline", 1.5);
        const int n = dim == 2 ? 12 : 8;
        sc.block(n, 0.995); // compressed: interior density about 1 % (2D) / 1.5 % (3D) above ρ0
        const double dx = 0.01, h = 1.5 * dx, rho0 = 1000, m = test::fluidOf(sc.s).particles.particleMass();
        const double w1 = cubicSplineDW(dx, h, dim), w2 = cubicSplineDW(std::sqrt(2.0) * dx, h, dim);
        const double sumSquares = dim == 2 ? 4 * w1 * w1 + 4 * w2 * w2 : 6 * w1 * w1 + 12 * w2 * w2;
        // one correction from the first prediction: with v = 0 and no other force, x* = x, so
        // p_i = δ (ρ_i − ρ0)
        auto p = sc.pressure("type pcisph; warmStart 0;", // the paper: p starts at 0
                              "maxDensityError 0; minIterations 1; maxIterations 1;");
        for (double dt : {1e-3, 5e-4}) {
            const double deltaHand = rho0 * rho0 / (2 * dt * dt * m * m * sumSquares);
            p->computeDensity(sc.s, test::fluidOf(sc.s), test::stepOf(sc.s));
            std::fill(test::fluidOf(sc.s).particles.acceleration().begin(), test::fluidOf(sc.s).particles.acceleration().end(), Vec3::Zero());
            p->addPressureAcceleration(sc.s, test::fluidOf(sc.s), test::stepOf(sc.s, dt));
            EXPECT_EQ(p->lastSolve().iterations, 1);
            const auto ids = sc.interior(n, 2);
            ASSERT_GT(ids.size(), 10u);
            for (std::size_t i : ids) {
                const double rhoErr = test::fluidOf(sc.s).particles.density()[i] - rho0;
                ASSERT_GT(rhoErr, 0) << dim << "D: the interior must be compressed";
                // float: δ and ρ − ρ0 (≈ 7 out of 1000) carry the rounding of ρ
                EXPECT_NEAR(test::fluidOf(sc.s).particles.pressure()[i] / (deltaHand * rhoErr), 1.0, test::tol(1e-6, 1e-5))
                    << dim << "D, dt " << dt << ": pressure " << test::fluidOf(sc.s).particles.pressure()[i] << " vs delta "
                    << deltaHand << " x " << rhoErr;
            }
        }
    }
}

TEST(Pcisph, ConvergesToMaximumDensityErrorAndTheStepRealisesThePrediction) {
    log::setQuiet(true);
    for (int dim : {2, 3}) {
        Scene sc(dim, "wendlandC2", 2.6);
        const int n = dim == 2 ? 20 : 10;
        sc.block(n, 0.99);
        const double eta = 1e-3, dt = 1e-3;
        auto p = sc.pressure("type pcisph;", "maxDensityError 0.001; minIterations 3; maxIterations 200;");
        p->computeDensity(sc.s, test::fluidOf(sc.s), test::stepOf(sc.s));
        const double before = sc.maxCompression();
        ASSERT_GT(before, 10 * eta);
        std::fill(test::fluidOf(sc.s).particles.acceleration().begin(), test::fluidOf(sc.s).particles.acceleration().end(), Vec3::Zero());
        p->addPressureAcceleration(sc.s, test::fluidOf(sc.s), test::stepOf(sc.s, dt));
        const SolverStats st = p->lastSolve();
        EXPECT_TRUE(st.converged);
        EXPECT_GE(st.iterations, 3);
        EXPECT_LT(st.iterations, 200);
        EXPECT_LE(st.maxDensityError, eta);
        EXPECT_LE(st.avgDensityError, st.maxDensityError);
        // pressure forces alone: total momentum unchanged
        Vec3 total = Vec3::Zero();
        double scale = 0;
        for (const auto& a : test::fluidOf(sc.s).particles.acceleration()) {
            total += a;
            scale += a.norm();
        }
        EXPECT_LT(total.norm(), test::tol(1e-10, 32 * test::eps) * scale); // float: ~30-term pair sums
        // the step taken with this acceleration lands on the verified prediction
        sc.advance(*p, dt);
        EXPECT_NEAR(sc.maxCompression(), st.maxDensityError, 1e-12) << dim << "D";
        std::cout << dim << "D block compressed " << 100 * before << " %: " << st.iterations
                  << " iterations to max error " << 100 * st.maxDensityError << " %\n";
    }
}

// The largest gain of PCISPH's correction on a pressure wave over the prototype lattice,
// against the same Fourier analysis done independently (Python, analytic kernels, a coarser
// grid of wave vectors): below 2 the paper's δ makes every wave converge, above 2 some diverge.
TEST(Pcisph, LatticeCorrectionGainMatchesTheFourierAnalysis) {
    log::setQuiet(true);
    struct Case {
        int dim;
        const char* kernel;
        double support, gain;
    };
    for (const Case& c : {Case{3, "cubicSpline", 2.0, 1.409}, Case{2, "cubicSpline", 2.0, 1.075},
                          Case{3, "wendlandC2", 2.6, 2.100}, Case{2, "wendlandC2", 2.6, 1.301},
                          Case{2, "wendlandC2", 4.0, 2.837}}) {
        Scene sc(c.dim, c.kernel, c.support);
        sc.block(4, 1.0); // tabulates the kernel
        const double gain = latticeMaxCorrectionGain(sc.s.kernel, sc.s.physics.particleSpacing, c.dim);
        EXPECT_NEAR(gain, c.gain, 0.02 * c.gain) << c.dim << "D " << c.kernel << " at " << c.support << " dx";
    }
}

// With a wide support (Wendland C2 at 4Δx in 2D: 44 neighbours, gain 2.84) the paper's δ
// overshoots on some waves and the correction diverges (200 iterations, the error grew from 1.2 %
// to 58 %); with δ scaled to a gain of 1.8 it converges.
TEST(Pcisph, ConvergesWithAWideSupport) {
    log::setQuiet(true);
    Scene sc(2, "wendlandC2", 4.0);
    sc.block(24, 0.99);
    auto p = sc.pressure("type pcisph;", "maxDensityError 0.001; minIterations 3; maxIterations 200;");
    p->computeDensity(sc.s, test::fluidOf(sc.s), test::stepOf(sc.s));
    ASSERT_GT(sc.maxCompression(), 0.01);
    std::fill(test::fluidOf(sc.s).particles.acceleration().begin(), test::fluidOf(sc.s).particles.acceleration().end(), Vec3::Zero());
    p->addPressureAcceleration(sc.s, test::fluidOf(sc.s), test::stepOf(sc.s, 1e-3));
    const SolverStats st = p->lastSolve();
    EXPECT_TRUE(st.converged);
    EXPECT_LE(st.maxDensityError, 0.001);
    std::cout << "2D block, Wendland C2 at 4 dx: " << st.iterations << " iterations to max error "
              << 100 * st.maxDensityError << " %\n";
}

TEST(Pcisph, StopsAtMaxIterationsAndSaysItDidNotConverge) {
    log::setQuiet(true);
    Scene sc(2, "wendlandC2", 2.6);
    sc.block(20, 0.99);
    auto p = sc.pressure("type pcisph;", "maxDensityError 1e-9; minIterations 3; maxIterations 4;");
    EXPECT_TRUE(p->isIterative());
    EXPECT_EQ(p->soundSpeed(sc.s.constants, sc.s.physics), 0);
    p->computeDensity(sc.s, test::fluidOf(sc.s), test::stepOf(sc.s));
    p->addPressureAcceleration(sc.s, test::fluidOf(sc.s), test::stepOf(sc.s, 1e-3));
    EXPECT_EQ(p->lastSolve().iterations, 4);
    EXPECT_FALSE(p->lastSolve().converged);
    EXPECT_GT(p->lastSolve().maxDensityError, 1e-9);
}

TEST(Pcisph, RejectsBadTolerances) {
    log::setQuiet(true);
    Scene sc(2, "wendlandC2", 2.6);
    sc.block(6, 1.0);
    EXPECT_THROW(sc.pressure("type pcisph;", "maxDensityError -1;"), InputError);
    EXPECT_THROW(sc.pressure("type pcisph;", "minIterations 5; maxIterations 2;"), InputError);
    EXPECT_THROW(sc.pressure("type pcisph;", "maxDensityErorr 0.01;"), InputError); // typo
    EXPECT_THROW(sc.pressure("type pcisph;", "densityErrorNorm median;"), InputError);
    EXPECT_THROW(sc.pressure("type pcisph; boundaryVolume random;", ""), InputError);
}

// ---------------------------------------------------------------------------------------------
// hydrostaticTank2D with pcisph

std::string readText(const fs::path& f) { return test::readFile(f); }
void writeText(const fs::path& f, const std::string& t) { std::ofstream(f) << t; }

// Replaces the body of the top-level dictionary 'name { ... }' (no nested braces inside).
std::string replaceBlock(const std::string& text, const std::string& name, const std::string& body) {
    const std::regex block("\n" + name + "\\s*\\{[^}]*\\}");
    EXPECT_TRUE(std::regex_search(text, block)) << name;
    return std::regex_replace(text, block, "\n" + name + "\n{\n    " + body + "\n}", std::regex_constants::format_first_only);
}

TEST(Pcisph, KeepsAHydrostaticColumnWithinEtaOfRestDensity) {
    log::setQuiet(true);
    test::TempDir tmp;
    const fs::path dir = tmp.path() / "tank";
    copyCaseInput(fs::path(SPINDRIFT_SOURCE_DIR) / "tutorials/hydrostaticTank2D", dir);
    std::string schemes = readText(dir / "system/sphSchemes");
    schemes = replaceBlock(schemes, "pressure", "type pcisph;");
    schemes = replaceBlock(schemes, "viscosity", "type artificial; alpha 0.1; soundSpeed 25;");
    writeText(dir / "system/sphSchemes", schemes);
    std::string control = readText(dir / "system/controlDict");
    control = std::regex_replace(control, std::regex("\nendTime[^;]*;"), "\nendTime 1;");
    control = std::regex_replace(control, std::regex("\nwriteInterval[^;]*;"), "\nwriteInterval 1;");
    control = std::regex_replace(control, std::regex("\nmaxCo[^;]*;"), "\nmaxCo 0.3;");
    control = std::regex_replace(control, std::regex("\nmaxDeltaT[^;]*;"), "\nmaxDeltaT 2e-3;");
    writeText(dir / "system/controlDict", control);
    const double eta = 0.01;
    writeText(dir / "system/sphSolution", "pressure { maxDensityError 0.01; minIterations 3; maxIterations 100; }\n");

    Simulation sim(dir);
    const RunSummary r = sim.run();
    EXPECT_GT(r.steps, 300);
    EXPECT_GT(r.averageIterations, 3.0);
    auto& s = sim.scene();
    // the density at the final state
    sim.evaluate(sim.scene().time, Scalar(2e-3));
    const double rho0 = s.physics.rho0, H = 0.3, g = 9.81, h = s.constants.supportRadius;
    double maxErr = 0, interiorDev = 0, vMax = 0, pBottom = 0, zBottom = 0;
    int nBottom = 0;
    for (std::size_t i = 0; i < test::fluidOf(s).particles.size(); ++i) {
        const Vec3 x = test::fluidOf(s).particles.position()[i];
        ASSERT_GE(x.x(), 0.0);
        ASSERT_LE(x.x(), 0.2);
        ASSERT_GE(x.y(), 0.0);
        const double rho = test::fluidOf(s).particles.density()[i];
        maxErr = std::max(maxErr, (rho - rho0) / rho0);
        if (x.y() < H - h) interiorDev = std::max(interiorDev, std::abs(rho - rho0) / rho0);
        vMax = std::max(vMax, double(test::fluidOf(s).particles.velocity()[i].norm()));
        if (x.y() < s.physics.particleSpacing) {
            pBottom += test::fluidOf(s).particles.pressure()[i];
            zBottom += x.y();
            ++nBottom;
        }
    }
    pBottom /= nBottom;
    zBottom /= nBottom;
    // row-mean pressure every 5 cm: it must fall with height (PCISPH's pressure is rebuilt
    // from zero every step, Algorithm 2 line 6, and stops at η, so it is not the full
    // hydrostatic pressure; it is printed against ρ0 g (H − z) for the record)
    double previous = std::numeric_limits<double>::infinity();
    for (double zr : {0.05, 0.1, 0.15, 0.2, 0.25}) {
        double pp = 0;
        int nn = 0;
        for (std::size_t i = 0; i < test::fluidOf(s).particles.size(); ++i)
            if (std::abs(test::fluidOf(s).particles.position()[i].y() - zr) < 0.005) {
                pp += test::fluidOf(s).particles.pressure()[i];
                ++nn;
            }
        ASSERT_GT(nn, 0);
        EXPECT_LT(pp / nn, previous) << "row at z = " << zr;
        previous = pp / nn;
    }
    const double pHydro = rho0 * g * (H - zBottom);
    std::cout << "pcisph hydrostatic column: " << r.steps << " steps, " << r.averageIterations
              << " iterations on average; final max density error " << 100 * maxErr << " %, interior |rho - rho0| "
              << 100 * interiorDev << " %, bottom pressure " << pBottom << " Pa vs " << pHydro << " Pa, max speed "
              << vMax << " m/s\n";
    EXPECT_LE(maxErr, eta);
    EXPECT_LE(interiorDev, eta);
    EXPECT_LT(vMax, 0.1);
}

// The speed benchmark's dam break (tutorials/benchmarks/damBreakCube3D: 6,859 particles,
// cubic spline, Akinci walls) at its reference Δt = 2 ms, through the front's impact on the
// side wall at t ≈ 0.35 s. The front's particles have few neighbours; with their own density
// in p/ρ² they got up to ten times the response δ predicts, a particle was thrown back from
// the wall at 38 m/s after 52 iterations and the run stopped on a blow-up.
TEST(Pcisph, RunsTheBenchmarkDamBreakAtTwoMillisecondsThroughTheWallImpact) {
    log::setQuiet(true);
    test::TempDir tmp;
    const fs::path dir = tmp.path() / "cube";
    copyCaseInput(fs::path(SPINDRIFT_SOURCE_DIR) / "tutorials/benchmarks/damBreakCube3D", dir);
    writeText(dir / "system/sphSchemes", replaceBlock(readText(dir / "system/sphSchemes"), "pressure", "type pcisph;"));
    std::string control = readText(dir / "system/controlDict");
    control = std::regex_replace(control, std::regex("\nendTime[^;]*;"), "\nendTime 0.4;");
    control = std::regex_replace(control, std::regex("\ndeltaT[^;]*;"), "\ndeltaT 2e-3;");
    control = std::regex_replace(control, std::regex("\nwriteInterval[^;]*;"), "\nwriteInterval 1;");
    writeText(dir / "system/controlDict", control);
    Simulation sim(dir);
    RunSummary r;
    ASSERT_NO_THROW(r = sim.run());
    EXPECT_EQ(r.steps, 200);
    EXPECT_LT(r.maxDensityError, 0.05); // 1.2–1.3 % (single precision 1.1–3.4 %, 7.0 % before the rising-error stop); 22 % when it blew up
    EXPECT_LT(r.averageIterations, 5.0); // 3.6
    double vMax = 0;
    for (const Vec3& v : test::fluidOf(sim.scene()).particles.velocity()) vMax = std::max(vMax, double(v.norm()));
    // The front runs at about 2 sqrt(g H) = 6 m/s. At the impact (Δt = 2 ms) a few particles
    // are pressed into the two-layer wall (up to 0.011 m past its face, in double precision too)
    // and pushed out again; whether one leaves a corner fast just before t = 0.4 turns on
    // round-off (in single precision 13 m/s at 23d3269, 7.7 m/s after a change of inlining
    // alone; double: 7.8 m/s). Thrown particles of a failing iteration went at
    // 24 m/s (single precision, before the iteration stopped on a rising error) and 38 m/s.
    EXPECT_LT(vMax, 18.0);
    std::cout << "pcisph benchmark dam break to 0.4 s: " << r.steps << " steps, " << r.averageIterations
              << " iterations on average, max density error " << 100 * r.maxDensityError << " %, max speed " << vMax
              << " m/s\n";
}

} // namespace
