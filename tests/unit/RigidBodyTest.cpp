// Rigid bodies (libsrc/RigidBody.hpp, constant/geometry `bodies`): Newton–Euler to round-off
// where the answer is exact (a ballistic flight, a torque-free spin), constraints, a body that
// meets the floor stops there, a body of the water's density stays where it is in still water, and
// a restart continues a body bit for bit.
#include "Case.hpp"
#include "Log.hpp"
#include "RigidBody.hpp"
#include "Simulation.hpp"
#include "TestSupport.hpp"

#include <gtest/gtest.h>
#include <fstream>
#ifdef _OPENMP
#include <omp.h>
#endif

using namespace spindrift;
namespace fs = std::filesystem;
using V3 = RigidBody::V3;
using M3 = RigidBody::M3;

namespace {

TEST(RigidBody, FallsOnTheBallisticTrajectoryToRoundOff) {
    RigidBody::State start;
    start.position = V3(0.1, 2.0, 0.3);
    start.velocity = V3(0.5, 3.0, -0.2);
    RigidBody body(2.0, M3::Identity(), start, 3);
    const V3 g(0, -9.81, 0);
    double t = 0;
    for (int n = 0; n < 1000; ++n) {
        const double dt = 1e-3 * (1 + 0.3 * std::sin(n)); // steps of varying size, as adjustTimeStep gives
        body.advance(dt, V3::Zero(), V3::Zero(), g);
        t += dt;
    }
    const V3 exact = start.position + t * start.velocity + 0.5 * t * t * g;
    EXPECT_LT((body.state().position - exact).norm(), 1e-13 * exact.norm());
    EXPECT_LT((body.state().velocity - (start.velocity + t * g)).norm(), 1e-13 * 30);
}

TEST(RigidBody, KeepsTheAngularMomentumOfATorqueFreeSpin) {
    RigidBody::State start;
    const M3 inertia = V3(1.0, 2.0, 3.5).asDiagonal();
    const V3 w0(0.3, 2.0, 0.4); // near the unstable middle axis: the axis of rotation wanders
    start.angularMomentum = inertia * w0;
    RigidBody body(1.0, inertia, start, 3);
    const double energy0 = 0.5 * w0.dot(inertia * w0);
    double worstEnergy = 0;
    for (int n = 0; n < 20000; ++n) {
        body.advance(1e-3, V3::Zero(), V3::Zero(), V3::Zero());
        const V3 w = body.angularVelocity();
        worstEnergy = std::max(worstEnergy, std::abs(0.5 * w.dot(body.state().angularMomentum) - energy0) / energy0);
    }
    EXPECT_EQ(body.state().angularMomentum, start.angularMomentum) << "L is kept exactly without a moment";
    EXPECT_NEAR(body.state().orientation.norm(), 1.0, 1e-12);
    EXPECT_LT(worstEnergy, 0.05) << "the explicit rotation keeps the energy within a few percent over 20 s";
    // the axis did wander (the test is not of a steady spin)
    EXPECT_GT((body.angularVelocity().normalized() - w0.normalized()).norm(), 0.1);
}

TEST(RigidBody, ConstraintsFixTheirAxes) {
    RigidBody::State start;
    start.velocity = V3(1, 1, 1);
    start.angularMomentum = V3(1, 1, 1);
    RigidBody body(1.0, M3::Identity(), start, 3);
    body.setConstraints({false, true, false}, {true, true, false}); // no y motion, rotation about z only
    for (int n = 0; n < 100; ++n) body.advance(1e-2, V3(0, 5, 0), V3(3, 3, 3), V3(0, -9.81, 0));
    EXPECT_EQ(body.state().position.y(), 0.0);
    EXPECT_EQ(body.state().velocity.y(), 0.0);
    EXPECT_NE(body.state().position.x(), 0.0);
    const V3 w = body.angularVelocity();
    EXPECT_EQ(w.x(), 0.0);
    EXPECT_EQ(w.y(), 0.0);
    EXPECT_GT(std::abs(w.z()), 1.0);
    // in 2D the body moves in the plane and turns about z whatever it is given
    RigidBody planar(1.0, M3::Identity(), RigidBody::State{}, 2);
    planar.advance(1e-2, V3(1, 1, 1), V3(1, 1, 1), V3::Zero());
    EXPECT_EQ(planar.state().position.z(), 0.0);
    EXPECT_EQ(planar.angularVelocity().x(), 0.0);
    EXPECT_GT(planar.angularVelocity().z(), 0.0);
}

void write(const fs::path& file, const std::string& text) {
    fs::create_directories(file.parent_path());
    std::ofstream(file) << text;
}

// A small case: a tank 0.5 m wide (walls, adami), water only in its own small tank far away, and
// a body released at rest, or water in the tank and a body in it ('bodyEntry': its dictionary).
fs::path bodyCase(const fs::path& dir, const std::string& fluidAndWalls, const std::string& body,
                  const std::string& endTime) {
    write(dir / "system/controlDict", "endTime " + endTime + ";\ndeltaT 1e-4;\nadjustTimeStep yes;\nmaxCo 0.15;\n"
                                      "maxDeltaT 1e-3;\nwriteControl adjustableRunTime;\nwriteInterval 0.02;\n");
    write(dir / "system/sphSchemes", "kernel { type wendlandC2; }\npressure { type wcsph; density continuity; }\n"
                                     "densityDiffusion { type antuono; }\nviscosity { type artificial; alpha 0.1; }\n"
                                     "integrator { type symplecticEuler; }\nboundary { type adami; }\n");
    write(dir / "constant/fluidProperties", "dimension 2;\nrho0 1000;\nviscosity 1e-6;\ngravity (0 -9.81 0);\n"
                                            "particleSpacing 0.02;\nsupportRadius 3;\n");
    write(dir / "constant/geometry", fluidAndWalls + "bodies\n{\n    block\n    {\n" + body + "    }\n}\n");
    return dir;
}

// constant/geometry's water 'depth' [m] deep in a 0.4 m wide tank 0.4 m high, open at the top
// ('extra': more of the water's entries)
std::string waterInSmallTank(const std::string& depth, const std::string& extra = "") {
    return "fluid { water { type box; min (0 0 0); max (0.4 " + depth + " 0); " + extra + "} }\n"
           "walls { tank { type container; min (0 0 0); max (0.4 0.4 0); layers 3; open (yMax); } }\n";
}

RigidBody::V3 bodyPosition(const fs::path& timeDir) {
    const Dictionary d = Dictionary::fromFile(timeDir / "uniform/bodies");
    const auto p = d.subDict("block").get<std::vector<double>>("position");
    return V3(p[0], p[1], p[2]);
}

TEST(RigidBody, WithoutFluidFallsBallisticallyThenStopsOnTheFloor) {
    log::setQuiet(true);
    test::TempDir tmp;
    const fs::path dir = bodyCase(tmp.path() / "case",
                                  "fluid { water { type box; min (2 0 0); max (2.1 0.1 0); } }\n"
                                  "walls\n{\n    tank { type container; min (0 0 0); max (0.5 0.6 0); layers 3; open (yMax); }\n"
                                  "    pool { type container; min (2 0 0); max (2.1 0.2 0); layers 3; open (yMax); }\n}\n",
                                  "        type box; min (0.2 0.3 0); max (0.3 0.36 0); density 500;\n", "0.4");
    Simulation sim(dir);
    sim.run();
    // in flight (the bottom at 0.3 m reaches the floor at t = sqrt(2 · 0.3 / g) = 0.247 s)
    const V3 x0(0.25, 0.33, 0);
    int checked = 0;
    for (const auto& [t, name] : CaseWriter(dir).existingTimes()) {
        const V3 x = bodyPosition(dir / name);
        if (t < 0.2) {
            const V3 exact = x0 + V3(0, -0.5 * 9.81 * t * t, 0);
            EXPECT_LT((x - exact).norm(), test::tol(1e-12, 1e-5)) << "t = " << t;
            ++checked;
        }
    }
    EXPECT_GE(checked, 9);
    // on the floor: the bottom face (0.03 below the centre) at the floor's face y = 0, at rest
    const auto& body = *sim.scene().find("block")->body;
    EXPECT_NEAR(body.state().position.y() - 0.03, 0.0, 0.1 * 0.02) << "not through the floor, not above it";
    EXPECT_LT(body.state().velocity.norm(), 0.05);
}

TEST(RigidBody, OfTheWatersDensityStaysPutInStillWater) {
    log::setQuiet(true);
    test::TempDir tmp;
    const fs::path dir = bodyCase(tmp.path() / "case", waterInSmallTank("0.3", "initialPressure hydrostatic; "),
                                  "        type box; min (0.14 0.1 0); max (0.26 0.2 0); density 1000;\n", "2");
    Simulation sim(dir);
    sim.run();
    const V3 start(0.2, 0.15, 0);
    const V3 drift = bodyPosition(dir / CaseWriter(dir).existingTimes().back().second) - start;
    EXPECT_LT(drift.norm(), 0.1 * 0.02) << "drift (" << drift.transpose() << ") over 2 s";
}

// A body's fastest particle counts in the CFL condition as the fluid's and a moving wall's do:
// Δt ≤ maxCo h / (c0 + |v|max), here the body's 5 m/s over still water.
TEST(RigidBody, ItsSpeedLimitsTheStep) {
    log::setQuiet(true);
    test::TempDir tmp;
    const fs::path dir = bodyCase(tmp.path() / "case", waterInSmallTank("0.1"),
                                  "        type box; min (0.14 0.2 0); max (0.26 0.3 0); density 500; velocity (0 -5 0);\n", "1");
    Simulation sim(dir);
    const Scene& s = sim.scene();
    const double c0 = s.constants.soundSpeed, h = s.constants.supportRadius;
    ASSERT_GT(c0, 0.0);
    EXPECT_LE(sim.stableDeltaT(), 0.15 * h / (c0 + 5) * (1 + 1e-6)) << "c0 " << c0 << ", h " << h;
}

// A floating box dropped into water, run to 0.16 s at once and in two halves (a restart from
// 0.08 s, at another thread count): the body's state and the fluid continue bit for bit.
TEST(RigidBody, ARestartContinuesTheBodyBitForBit) {
    log::setQuiet(true);
    test::TempDir tmp;
    const std::string water = "fluid { water { type box; min (0 0 0); max (0.4 0.2 0); initialPressure hydrostatic; } }\n"
                              "walls { tank { type container; min (0 0 0); max (0.4 0.4 0); layers 3; open (yMax); } }\n";
    const std::string box = "        type box; min (0.14 0.22 0); max (0.26 0.28 0); density 500;\n";
    const fs::path whole = bodyCase(tmp.path() / "whole", water, box, "0.16");
    Simulation(whole).run();
    const fs::path split = bodyCase(tmp.path() / "split", water, box, "0.08");
    Simulation(split).run();
    std::string control = test::readFile(split / "system/controlDict");
    control = "startFrom latestTime;\n" + control;
    control.replace(control.find("endTime 0.08;"), 13, "endTime 0.16;");
    write(split / "system/controlDict", control);
#ifdef _OPENMP
    const int threads = omp_get_max_threads();
    omp_set_num_threads(threads == 1 ? 2 : 1);
#endif
    Simulation(split).run();
#ifdef _OPENMP
    omp_set_num_threads(threads);
#endif
    // the box fell in and moves (the comparison is not of a body at rest)
    const V3 end = bodyPosition(whole / "0.16");
    EXPECT_LT(end.y(), 0.25 - 0.02) << "the box fell into the water";
    EXPECT_EQ(test::readFile(whole / "0.16/uniform/bodies"), test::readFile(split / "0.16/uniform/bodies"));
    const ParticleSet a = readVtp(whole / "0.16/fluid.vtp"), b = readVtp(split / "0.16/fluid.vtp");
    EXPECT_EQ(a.position(), b.position());
    EXPECT_EQ(a.velocity(), b.velocity());
    const ParticleSet ba = readVtp(whole / "0.16/block.vtp", "block"), bb = readVtp(split / "0.16/block.vtp", "block");
    EXPECT_EQ(ba.position(), bb.position());
}

} // namespace
