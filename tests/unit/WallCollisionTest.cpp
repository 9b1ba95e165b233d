// The collision of fluid particles with the walls (libsrc/WallCollision.hpp), which every boundary
// model applies after the pressure model: a particle the step would carry across a wall's face
// leaves with its normal velocity reversed and scaled by the restitution, its slide reduced by
// Coulomb friction, and nothing happens to a particle that stays clear or moves away. On by
// default (restitution 0: the crossing is stopped); `collision no;` switches it off.
#include "BoundaryModel.hpp"
#include "TestSupport.hpp"

#include <algorithm>
#include <limits>
#include <gtest/gtest.h>

namespace {
using namespace spindrift;

// The step moves the particle 0.2 dx, on the neighbour lists of its start: the wall's normal at
// the end of the step is read from those pairs (a few at the support's edge are missed).
constexpr double tolerance = 1e-3;
constexpr Scalar dt = Scalar(0.002);

struct Floor {
    Scene s;
    std::unique_ptr<Kernel> kernel;
    std::unique_ptr<BoundaryModel> boundary;
    // one fluid particle at height·dx above the face y = 0 of a floor of four lattice layers,
    // symmetric about x = 0, with velocity v, placed so that the step takes it to x = 0 (between
    // two wall particles, where the wall's normal is (0, 1): elsewhere the bumps of its particles
    // tilt it by a few degrees this near the face); the boundary model from 'dict'
    Floor(const std::string& dict, double height, const Vec3& v, int length = 10) {
        s.physics = test::physicsFor(2, 0.01, 2.6);
        kernel = test::createModel<Kernel>("type wendlandC2;", s.physics);
        const double dx = s.physics.particleSpacing;
        test::fillLattice(s, *kernel, Vec3::Zero(), Vec3(dx, dx, 0));
        ParticleSystem& fluid = test::fluidOf(s);
        fluid.particles.position()[0] = Vec3(-dt * v[0], Scalar(height * dx), 0);
        fluid.particles.velocity()[0] = v;
        fluid.particles.acceleration()[0] = Vec3::Zero();
        std::vector<Vec3> wall;
        for (int layer = 0; layer < 4; ++layer)
            for (int i = -10; i < length; ++i) wall.emplace_back(Scalar((i + 0.5) * dx), Scalar(-(layer + 0.5) * dx), 0);
        test::addWallSystem(s, "floor", wall);
        test::rebuild(s);
        boundary = test::createModel<BoundaryModel>(dict, s.physics);
        boundary->initialise(s);
    }
    // the velocity at the end of a step of dt: v + dt a after the collision
    Vec3 velocityAfter() {
        ParticleSystem& fluid = test::fluidOf(s);
        boundary->correctAcceleration(s, fluid, test::stepOf(s, dt));
        return fluid.particles.velocity()[0] + dt * fluid.particles.acceleration()[0];
    }
};


TEST(WallCollision, ACrossingParticleIsReflectedWithRestitutionAndFriction) {
    for (const char* model : {"adami", "akinci"}) {
        // 0.1 dx over the face, falling 0.2 dx in the step at 1 m/s, sliding at 1 m/s
        Floor f(std::string("type ") + model + "; collision { restitution 0.5; friction 0.2; }", 0.1, Vec3(1, -1, 0));
        const Vec3 v = f.velocityAfter();
        EXPECT_NEAR(v[1], 0.5, tolerance) << model; // −e u_n
        // the friction impulse μ (1 + e) |u_n| = 0.3 of the slide
        EXPECT_NEAR(v[0], 0.7, tolerance) << model;
    }
}

TEST(WallCollision, FrictionStopsASlideButNeverReversesIt) {
    Floor f("type adami; collision { restitution 0; friction 2; }", 0.1, Vec3(0.5, -1, 0));
    const Vec3 v = f.velocityAfter();
    EXPECT_NEAR(v[0], 0.0, tolerance);
    EXPECT_NEAR(v[1], 0.0, tolerance);
}

TEST(WallCollision, ContactDistanceStopsTheApproachAndKeepsTheSlide) {
    // adami's contactDistance 0.25: the particle would end 0.15 dx from the face
    Floor f("type adami; contactDistance 0.25;", 0.25, Vec3(1, -0.5, 0));
    const Vec3 v = f.velocityAfter();
    EXPECT_NEAR(v[1], 0.0, tolerance);
    EXPECT_NEAR(v[0], 1.0, tolerance);
}

TEST(WallCollision, AParticleThatStaysClearOrLeavesIsUntouched) {
    // ends 0.1 dx above the face: not a crossing with distance 0
    Floor clear("type adami; collision { restitution 1; friction 1; }", 0.2, Vec3(1, -0.5, 0));
    const Vec3 v1 = clear.velocityAfter();
    EXPECT_EQ(v1, Vec3(1, -0.5, 0));
    // already at the face but moving away
    Floor leaving("type adami; collision { restitution 1; friction 1; }", 0.1, Vec3(1, 0.5, 0));
    const Vec3 v2 = leaving.velocityAfter();
    EXPECT_EQ(v2, Vec3(1, 0.5, 0));
    // collision switched off: nothing is done
    Floor off("type adami; collision no;", 0.1, Vec3(1, -1, 0));
    const Vec3 v3 = off.velocityAfter();
    EXPECT_EQ(v3, Vec3(1, -1, 0));
}

// The share's normal is tilted by the bumps of the wall's particles this near the face, and
// stopping the approach along it let a particle sliding along a floor creep past the face step by
// step (0.02 dx in Colagrossi's dam break at H/80): pulled down by gravity and sliding at 1 m/s,
// 0.2 dx a step, over 50 dx of floor, it now ends no step past the face.
TEST(WallCollision, AParticleSlidingAlongAFloorNeverEndsAStepPastItsFace) {
    for (const double start : {0.0, 0.3}) { // on the face; 0.3 dx over it, falling onto it
        Floor f("type adami;", start, Vec3(1, 0, 0), 70);
        ParticleSystem& fluid = test::fluidOf(f.s);
        const Scalar dx = f.s.physics.particleSpacing;
        double lowest = start;
        for (int step = 0; step < 250; ++step) {
            fluid.particles.acceleration()[0] = Vec3(0, Scalar(-9.81), 0);
            const Vec3 v = f.velocityAfter();
            fluid.particles.velocity()[0] = v;
            fluid.particles.position()[0] += dt * v;
            test::rebuild(f.s);
            lowest = std::min(lowest, double(fluid.particles.position()[0][1] / dx));
        }
        // past it by no more than the first-order estimate of the share's distance allows
        EXPECT_GE(lowest, -1e-4) << "started " << start << " dx over the face";
        EXPECT_LT(lowest, 0.01) << "it reached the face"; // and was held there, not lifted
        EXPECT_NEAR(fluid.particles.velocity()[0][0], 1.0, 0.03); // the slide kept (the tilt brakes it 2 %)
    }
}

TEST(WallCollision, ByDefaultEveryBoundaryModelStopsACrossing) {
    for (const char* model : {"type adami;", "type akinci;", "type adami; collision yes;"}) {
        Floor f(model, 0.1, Vec3(1, -1, 0));
        const Vec3 v = f.velocityAfter();
        EXPECT_NEAR(v[1], 0.0, tolerance) << model;
        EXPECT_NEAR(v[0], 1.0, tolerance) << model;
    }
}

// A single layer on a surface (a Poisson-disk mesh wall): its particles carry the surface's
// normal, and the collision reads the surface from them, not from the layer's share (which
// peaks on the layer and, near a corner, points along the other faces: a 3D tank let a particle
// through its floor).
struct Sheet {
    Scene s;
    std::unique_ptr<Kernel> kernel;
    std::unique_ptr<BoundaryModel> boundary;
    // the layer y = 0 of particles 0.5 dx apart (normals alternately up and down: either
    // orientation), one fluid particle 'height' dx above it (below: negative) with velocity v,
    // placed so that the step takes it to x = 0.1 dx
    Sheet(const std::string& dict, double height, const Vec3& v) {
        s.physics = test::physicsFor(2, 0.01, 2.6);
        kernel = test::createModel<Kernel>("type wendlandC2;", s.physics);
        const double dx = s.physics.particleSpacing;
        test::fillLattice(s, *kernel, Vec3::Zero(), Vec3(dx, dx, 0));
        ParticleSystem& fluid = test::fluidOf(s);
        fluid.particles.position()[0] = Vec3(Scalar(0.1 * dx) - dt * v[0], Scalar(height * dx), 0);
        fluid.particles.velocity()[0] = v;
        fluid.particles.acceleration()[0] = Vec3::Zero();
        std::vector<Vec3> layer, normals;
        for (int i = -20; i <= 20; ++i) {
            layer.emplace_back(Scalar(i * 0.5 * dx), 0, 0);
            normals.emplace_back(0, i % 2 ? 1 : -1, 0);
        }
        ParticleSystem& sheet = test::addWallSystem(s, "sheet", layer);
        sheet.surfaceNormal = &sheet.particles.addVector("surfaceNormal", {.output = false, .scratch = true});
        *sheet.surfaceNormal = normals;
        sheet.surfaceSpacing = Scalar(0.5 * dx);
        test::rebuild(s);
        boundary = test::createModel<BoundaryModel>(dict, s.physics);
        boundary->initialise(s);
        s.reactions.want(sheet.index);
    }
    Vec3 velocityAfter() {
        ParticleSystem& fluid = test::fluidOf(s);
        const Step step = test::stepOf(s, dt);
        boundary->correctAcceleration(s, fluid, step);
        s.reactions.clear();
        boundary->addReactions(s, fluid, step, s.reactions);
        return fluid.particles.velocity()[0] + dt * fluid.particles.acceleration()[0];
    }
};

TEST(WallCollision, ASingleLayerKeepsParticlesOnTheirSide) {
    // its face lies a quarter spacing in front of the layer
    for (const char* model : {"type adami;", "type akinci;", "type adami; collision { restitution 0.5; }"}) {
        const double e = std::string(model).find("restitution") != std::string::npos ? 0.5 : 0;
        for (const double side : {1.0, -1.0}) {
            // 0.35 dx from the layer, crossing its face in the step (0.2 dx at 1 m/s), sliding at 1 m/s
            Sheet f(model, 0.35 * side, Vec3(1, Scalar(-side), 0));
            const Vec3 v = f.velocityAfter();
            EXPECT_NEAR(v[1], e * side, tolerance) << model << " side " << side;
            EXPECT_NEAR(v[0], 1.0, tolerance) << model << " side " << side;
            // the layer takes the reaction: −m Δv/Δt
            const ParticleSystem& fluid = test::fluidOf(f.s);
            const double m = double(fluid.particles.particleMass());
            const Wrench w = f.s.reactions.total(f.s.systems.back()->index);
            // to the rounding of the build's Scalar (float: 1e-5 of m/dt)
            const double roundoff = std::max(1e-9, 100.0 * double(std::numeric_limits<Scalar>::epsilon()));
            EXPECT_NEAR(w.force[1], -m * (v[1] + side) / double(dt), roundoff * m / double(dt)) << model;
            EXPECT_NEAR(w.force[0], 0, roundoff * m / double(dt)) << model;
        }
    }
    // clear of it (ends 1.1 dx from the layer), or moving away: untouched
    Sheet clear("type adami;", 1.2, Vec3(1, -0.5, 0));
    EXPECT_EQ(clear.velocityAfter(), Vec3(1, -0.5, 0));
    Sheet leaving("type adami;", -0.2, Vec3(1, -1, 0));
    EXPECT_EQ(leaving.velocityAfter(), Vec3(1, -1, 0));
    // ending 0.7 dx from it: 'distance 0.5' (0.75 dx) stops the approach
    Sheet contact("type adami; collision { distance 0.5; }", 0.8, Vec3(1, -0.5, 0));
    EXPECT_NEAR(contact.velocityAfter()[1], 0.0, tolerance);
}

TEST(WallCollision, BadOptionsAreRefusedWithTheirKeyword) {
    const auto physics = test::physicsFor(2);
    for (const char* bad : {"collision { restitution 1.5; }", "collision { friction -1; }", "collision { distance 0.7; }",
                            "collision { restitution 0.5; spin 1; }", "contactDistance 0.2; collision { }"}) {
        EXPECT_THROW(test::createModel<BoundaryModel>(std::string("type adami; ") + bad, physics), InputError) << bad;
    }
}

} // namespace
