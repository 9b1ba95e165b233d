// diffuseParticles (plugins/passive): spray flies the ballistic parabola to round-off; foam on a
// still surface stays where it is and expires after its lifetime; an air bubble rises to the
// surface and turns to foam there; one flying into a wall is deleted at its face; a uniform
// flow generates nothing, a disordered one generates
// particles, the same at any thread count and capped at maxParticles; the state a restart needs
// is written and read back, and a restart continues bit for bit; the water is the same without
// them.
#include "Log.hpp"
#include "Simulation.hpp"
#include "TestSupport.hpp"

#include <gtest/gtest.h>

#include <omp.h>

#include <filesystem>

#include <cmath>
#include <random>
#include <set>

using namespace spindrift;

namespace {

constexpr double dx = 0.01;

// A block of fluid on the lattice, [0, n dx)^d, at rest (density ρ0), and the model made from
// sphSchemes text as the passive entry 'diffuse'.
struct DiffuseScene {
    Scene s;
    std::unique_ptr<Kernel> kernel;
    std::unique_ptr<Dictionary> dict;
    std::unique_ptr<PassiveModel> model;
    int dim, n;

    // (floor: three rows of wall particles under the block and 8 spacings either side of it, 2D)
    DiffuseScene(int dim_, int n_, const std::string& options = "", bool floor = false) : dim(dim_), n(n_) {
        s.physics = test::physicsFor(dim, dx, 2.6, 1000);
        s.physics.gravity = dim == 2 ? Vec3(0, -9.81, 0) : Vec3(0, 0, -9.81);
        kernel = test::createModel<Kernel>("type wendlandC2;", s.physics);
        const Vec3 hi = Vec3(n * dx, n * dx, dim == 3 ? n * dx : 0);
        test::fillLattice(s, *kernel, Vec3::Zero(), hi);
        if (floor) {
            std::vector<Vec3> rows;
            for (int l = 0; l < 3; ++l)
                for (int i = -8; i < n + 8; ++i) rows.emplace_back((i + 0.5) * dx, -(l + 0.5) * dx, 0);
            test::addWallSystem(s, "floor", rows);
            test::setWallMasses(s, test::fluidOf(s).particles.particleMass());
        }
        dict = std::make_unique<Dictionary>(Dictionary::fromString("type diffuseParticles; " + options, "sphSchemes.passive.diffuse"));
        model = ModelRegistry::instance().create<PassiveModel>(*dict, s.physics, s.constants, nullptr, ".", "diffuse");
        model->initialise(s);
        test::rebuild(s);
    }
    ParticleSystem& fluid() { return test::fluidOf(s); }
    ParticleSystem& diffuse() { return *s.find("diffuse"); }
    // a diffuse particle at x moving with v (its type is set by the next step)
    void add(const Vec3& x, const Vec3& v, double lifetime = 1) {
        auto& set = diffuse().particles;
        set.append(x, v, Index(1000000 + set.size()));
        set.findScalar("lifetime")->back() = Scalar(lifetime);
        test::rebuild(s);
    }
    void step(double dt) {
        model->afterStep(s, test::stepOf(s, Scalar(dt)));
        ++s.step;
        s.time += dt;
        test::rebuild(s);
    }
    Scalar type(std::size_t i) { return (*diffuse().particles.findScalar("type"))[i]; }
    int up() const { return dim - 1; }
};

TEST(DiffuseParticles, SprayFliesTheBallisticParabola) {
    for (int dim : {2, 3}) {
        DiffuseScene sc(dim, 6);
        // (clear of the fluid's support all the way, inside the search's domain)
        const Vec3 x0 = dim == 2 ? Vec3(-0.05, 0.07, 0) : Vec3(-0.05, 0.03, 0.07), v0 = dim == 2 ? Vec3(1, 1.5, 0) : Vec3(1, 0.2, 1.5);
        sc.add(x0, v0);
        const double dt = 1e-3;
        for (int k = 0; k < 60; ++k) sc.step(dt);
        ASSERT_EQ(sc.diffuse().size(), 1u);
        const double t = 60 * dt;
        const Vec3 g = sc.s.physics.gravity;
        const Vec3 expected = x0 + t * v0 + 0.5 * t * t * g;
        EXPECT_EQ(sc.type(0), 0) << "spray";
        EXPECT_LT((sc.diffuse().particles.position()[0] - expected).norm(), test::tol(1e-12, 1e-5)) << dim << "D";
        EXPECT_LT((sc.diffuse().particles.velocity()[0] - (v0 + t * g)).norm(), test::tol(1e-12, 1e-5)) << dim << "D";
    }
}

TEST(DiffuseParticles, SprayIntoAWallIsDeletedAtItsFace) {
    DiffuseScene sc(2, 6, "", true);
    sc.add(Vec3(-0.05, 0.03, 0), Vec3(0, -1, 0)); // beside the block, falling onto the floor (face y = 0)
    int steps = 0;
    while (sc.diffuse().size() == 1 && steps < 200) {
        const double y = sc.diffuse().particles.position()[0][1];
        EXPECT_GT(y, -0.5 * dx) << "still there past the face, step " << steps;
        sc.step(1e-3);
        ++steps;
    }
    EXPECT_EQ(sc.diffuse().size(), 0u) << "deleted once past the floor's face";
    EXPECT_GT(steps, 20) << "not before reaching it";
}

TEST(DiffuseParticles, FoamOnAStillSurfaceStaysAndExpires) {
    DiffuseScene sc(3, 10, "lifetime 0.05;");
    const int up = sc.up();
    std::vector<Vec3> start;
    for (double a : {0.035, 0.055, 0.065})
        for (double b : {0.045, 0.055}) {
            Vec3 x(a, b, 0);
            x[up] = 10 * dx; // half a spacing above the top row: about half a neighbourhood
            sc.add(x, Vec3::Zero(), 0.05);
            start.push_back(x);
        }
    for (int k = 0; k < 4; ++k) sc.step(0.01);
    ASSERT_EQ(sc.diffuse().size(), start.size());
    for (std::size_t i = 0; i < start.size(); ++i) {
        EXPECT_EQ(sc.type(i), 1) << "foam";
        EXPECT_LT((sc.diffuse().particles.position()[i] - start[i]).norm(), 1e-12) << "carried by water at rest";
    }
    sc.step(0.01); // its lifetime, 0.05 s, is over
    EXPECT_EQ(sc.diffuse().size(), 0u);
}

TEST(DiffuseParticles, BubbleRisesToTheSurfaceAndTurnsToFoam) {
    DiffuseScene sc(3, 10);
    const int up = sc.up();
    Vec3 x(0.05, 0.05, 0.05);
    sc.add(x, Vec3::Zero());
    sc.step(5e-3);
    EXPECT_EQ(sc.type(0), 2) << "a bubble inside the water";
    int steps = 0; // (rising at k_b |g| Δt/k_d = 0.08 m/s)
    while (sc.type(0) == 2 && steps < 1000) {
        sc.step(5e-3);
        ++steps;
    }
    EXPECT_EQ(sc.type(0), 1) << "foam once it reaches the surface, after " << steps << " steps";
    const double height = sc.diffuse().particles.position()[0][up];
    EXPECT_GT(height, 9 * dx);
    EXPECT_LT(height, 11 * dx);
}

// a disordered velocity field (uniform random components of ±amplitude) on the block
void stir(DiffuseScene& sc, double amplitude, unsigned seed = 5) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-amplitude, amplitude);
    for (auto& v : sc.fluid().particles.velocity()) v = Vec3(u(rng), u(rng), sc.dim == 3 ? u(rng) : 0.0);
}

const std::string eager = "trappedAir (0.1 2); kineticEnergy (0 0.5); kTrappedAir 2000; ";

TEST(DiffuseParticles, AUniformFlowGeneratesNothing) {
    DiffuseScene sc(2, 12, eager);
    for (auto& v : sc.fluid().particles.velocity()) v = Vec3(3, 1, 0);
    sc.step(1e-3);
    EXPECT_EQ(sc.diffuse().size(), 0u);
}

TEST(DiffuseParticles, DisorderedFlowGeneratesTheSameParticlesAtAnyThreadCount) {
    std::vector<Vec3> x[2];
    std::vector<Index> ids[2];
    std::string state[2];
    for (int threads : {1, 2}) {
        const int saved = omp_get_max_threads();
        omp_set_num_threads(threads);
        DiffuseScene sc(2, 12, eager);
        stir(sc, 1.0);
        sc.step(1e-3);
        sc.step(1e-3);
        omp_set_num_threads(saved);
        x[threads - 1] = sc.diffuse().particles.position();
        ids[threads - 1] = sc.diffuse().particles.id();
        state[threads - 1] = sc.model->stateText();
    }
    std::cout << x[0].size() << " diffuse particles from 144 stirred fluid particles in two steps\n";
    EXPECT_GT(x[0].size(), 10u);
    EXPECT_EQ(x[0], x[1]);
    EXPECT_EQ(ids[0], ids[1]);
    EXPECT_EQ(state[0], state[1]);
    EXPECT_EQ(std::set<Index>(ids[0].begin(), ids[0].end()).size(), ids[0].size()) << "ids unique";
}

TEST(DiffuseParticles, CapAndRestartState) {
    DiffuseScene sc(2, 12, eager + "maxParticles 7;");
    stir(sc, 1.0);
    sc.step(1e-3);
    sc.step(1e-3);
    EXPECT_EQ(sc.diffuse().size(), 7u);
    // the state a restart reads back: the next id, so that a new particle never takes an old one's
    const std::string state = sc.model->stateText();
    EXPECT_NE(state.find("nextId 7;"), std::string::npos) << state;
    DiffuseScene other(2, 12, eager);
    other.model->readState(Dictionary::fromString(state, "uniform/passive.diffuse"));
    EXPECT_EQ(other.model->stateText(), state);
}

TEST(DiffuseParticles, BadOptionsNameTheirKeyword) {
    for (const std::string& text : {std::string("trappedAir (5);"), std::string("waveCrest (8 2);"), std::string("drag 2;"),
                                    std::string("lifetime -1;"), std::string("sprayNeighbours 30; bubbleNeighbours 10;")}) {
        try {
            DiffuseScene sc(2, 4, text);
            ADD_FAILURE() << "accepted: " << text;
        } catch (const InputError& e) {
            const std::string key = text.substr(0, text.find(' '));
            EXPECT_NE(std::string(e.what()).find(key == "sprayNeighbours" ? "Neighbours" : key), std::string::npos) << e.what();
        }
    }
}

} // namespace

namespace {

// Two blocks of water meeting head-on at 2 m/s each (no walls, no gravity): air is trapped where
// they meet from the first step, so diffuse particles are generated at once.
std::filesystem::path collidingBlocks(const test::TempDir& tmp, const std::string& name, const std::string& timing,
                                      bool diffuse = true) {
    // (adjustableRunTime: the step that lands on the restart time is the same in both runs)
    tmp.writeFile(name + "/system/controlDict", timing + "deltaT 2e-4;\nwriteControl adjustableRunTime;\nwriteInterval 0.005;\n");
    tmp.writeFile(name + "/system/sphSchemes", "kernel { type wendlandC2; }\npressure { type wcsph; soundSpeed 40; }\n"
                                               "integrator { type symplecticEuler; }\n" +
                                                   (diffuse ? "passive { diffuse { type diffuseParticles; " + eager + "} }\n" : ""));
    tmp.writeFile(name + "/constant/fluidProperties", "dimension 2;\nrho0 1000;\nparticleSpacing 0.01;\nsupportRadius 2.6;\n"
                                                      "gravity (0 0 0);\n");
    tmp.writeFile(name + "/constant/geometry",
                  "fluid { left { type box; min (0 0 0); max (0.1 0.1 0); velocity (2 0 0); }\n"
                  "        right { type box; min (0.12 0 0); max (0.22 0.1 0); velocity (-2 0 0); } }\n");
    return tmp.path() / name;
}

TEST(DiffuseParticles, RestartContinuesBitForBit) {
    log::setQuiet(true);
    test::TempDir tmp;
    const auto whole = collidingBlocks(tmp, "whole", "endTime 0.02;\n");
    Simulation(whole).run();
    const auto split = collidingBlocks(tmp, "split", "endTime 0.01;\n");
    Simulation(split).run();
    EXPECT_TRUE(std::filesystem::exists(split / "0.01/uniform/passive"));
    collidingBlocks(tmp, "split", "startFrom latestTime;\nendTime 0.02;\n");
    Simulation(split).run();
    {
        const ParticleSet fa = readVtp(whole / "0.02/fluid.vtp"), fb = readVtp(split / "0.02/fluid.vtp");
        EXPECT_EQ(fa.position(), fb.position()) << "the fluid";
        const ParticleSet a1 = readVtp(whole / "0.01/diffuse.vtp"), b1 = readVtp(split / "0.01/diffuse.vtp");
        EXPECT_EQ(a1.position(), b1.position()) << "at the restart time";
        EXPECT_EQ(a1.velocity(), b1.velocity()) << "at the restart time";
    }
    const ParticleSet a = readVtp(whole / "0.02/diffuse.vtp"), b = readVtp(split / "0.02/diffuse.vtp");
    std::cout << a.size() << " diffuse particles at 0.02 s\n";
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a.position()[i] != b.position()[i] || a.id()[i] != b.id()[i]) {
            ADD_FAILURE() << "first difference at " << i << ": id " << a.id()[i] << " / " << b.id()[i] << ", x "
                          << a.position()[i].transpose() << " / " << b.position()[i].transpose();
            break;
        }
    EXPECT_GT(a.size(), 0u);
    EXPECT_EQ(a.position(), b.position());
    EXPECT_EQ(a.velocity(), b.velocity());
    EXPECT_EQ(a.id(), b.id());
    EXPECT_EQ(*a.findScalar("type"), *b.findScalar("type"));
    // they never act on the water: the same run without them has the same water
    const auto without = collidingBlocks(tmp, "without", "endTime 0.02;\n", false);
    Simulation(without).run();
    const ParticleSet f = readVtp(whole / "0.02/fluid.vtp"), g = readVtp(without / "0.02/fluid.vtp");
    EXPECT_EQ(f.position(), g.position());
    EXPECT_EQ(f.velocity(), g.velocity());
}

} // namespace
