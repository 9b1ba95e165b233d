// constant/geometry's shapes (issue 38.2, Shape.hpp): each primitive's inside and outside, its
// particles' area or volume against the analytic one within the lattice's error (half a spacing
// over the surface), a subtraction, overlapping regions merged once, a body's mass from its
// shape, a wall box off the lattice refused, and initial fields from expressions (Expression.hpp).
#include "Expression.hpp"
#include "Geometry.hpp"
#include "Log.hpp"
#include "Shape.hpp"

#include <gtest/gtest.h>
#include <cmath>
#include <numbers>

using namespace spindrift;

namespace {

const double pi = std::numbers::pi;

std::unique_ptr<Shape> shape(const std::string& text, int dim, Scalar dx = Scalar(0.01)) {
    const Dictionary d = Dictionary::fromString(text, "geometry");
    return readShape(d, dim, dx);
}

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

std::size_t count(const Shape& s, Scalar dx) {
    std::vector<Vec3> p;
    sampleShape(s, dx, 0, p);
    return p.size();
}

// (the tolerance: the lattice's error, half a spacing over the surface, plus single precision)
void expectMeasure(double measured, double exact, double surface, double dx, const std::string& what) {
    EXPECT_NEAR(measured, exact, 0.5 * surface * dx) << what;
    EXPECT_NE(measured, 0) << what;
}

SampledGeometry sample(const std::string& text, Scalar dx, int dim) {
    return sampleGeometry(Dictionary::fromString(text, "geometry"), dx, dim);
}

} // namespace

TEST(Shape, CircleInsideOutsideAndArea) {
    const auto c = shape("type cylinder; centre (0.3 -0.2 0); radius 0.5;", 2);
    EXPECT_NEAR(c->signedDistance(Vec3(0.3, -0.2, 0)), -0.5, 1e-6);
    EXPECT_NEAR(c->signedDistance(Vec3(0.3, 0.5, 7)), 0.2, 1e-6) << "2D: z ignored";
    EXPECT_TRUE(c->contains(Vec3(0.7, -0.2, 0)));
    EXPECT_FALSE(c->contains(Vec3(0.81, -0.2, 0)));
    for (const double dx : {0.05, 0.02, 0.01}) {
        const double area = double(count(*c, Scalar(dx))) * dx * dx;
        expectMeasure(area, pi * 0.25, 2 * pi * 0.5, dx, "circle, dx " + std::to_string(dx));
    }
    // a sphere in 2D is the same circle
    const auto s = shape("type sphere; centre (0.3 -0.2 0); radius 0.5;", 2);
    EXPECT_EQ(count(*s, Scalar(0.02)), count(*c, Scalar(0.02)));
}

TEST(Shape, SphereVolume) {
    const auto s = shape("type sphere; centre (0.1 0.2 0.3); radius 0.25;", 3);
    EXPECT_NEAR(s->signedDistance(Vec3(0.1, 0.2, 0.65)), 0.1, 1e-6);
    const double dx = 0.0125;
    expectMeasure(double(count(*s, Scalar(dx))) * dx * dx * dx, 4.0 / 3 * pi * std::pow(0.25, 3),
                  4 * pi * 0.25 * 0.25, dx, "sphere");
}

TEST(Shape, ObliqueCylinderVolumeAndCaps) {
    // axis from (0 0 0) to (0.3 0.4 0): length 0.5
    const auto c = shape("type cylinder; point1 (0 0 0); point2 (0.3 0.4 0); radius 0.1;", 3);
    EXPECT_NEAR(c->signedDistance(Vec3(0.15, 0.2, 0)), -0.1, 1e-6) << "on the axis, mid-way";
    EXPECT_NEAR(c->signedDistance(Vec3(-0.3, -0.4, 0)), 0.5, 1e-6) << "beyond a cap on the axis";
    EXPECT_NEAR(c->signedDistance(Vec3(0.15, 0.2, 0.3)), 0.2, 1e-6) << "beside it";
    Vec3 lo, hi;
    c->bounds(lo, hi);
    EXPECT_NEAR(hi[2], 0.1, 1e-6);
    EXPECT_NEAR(lo[0], -0.08, 1e-6); // r sin(angle of the axis to x) = 0.1 * 0.8
    const double dx = 0.01;
    expectMeasure(double(count(*c, Scalar(dx))) * dx * dx * dx, pi * 0.01 * 0.5, 2 * pi * 0.1 * 0.5 + 2 * pi * 0.01,
                  dx, "cylinder");
}

TEST(Shape, PolygonConcaveEitherOrientationAndABeach) {
    // an L: the notch (0.5..1, 0.5..1) is outside; area 0.75
    const std::string points = "(0 0 0) (1 0 0) (1 0.5 0) (0.5 0.5 0) (0.5 1 0) (0 1 0)";
    const auto l = shape("type polygon; points (" + points + ");", 2);
    const auto reversed = shape("type polygon; points ((0 1 0) (0.5 1 0) (0.5 0.5 0) (1 0.5 0) (1 0 0) (0 0 0));", 2);
    EXPECT_FALSE(l->contains(Vec3(0.75, 0.75, 0)));
    EXPECT_TRUE(l->contains(Vec3(0.25, 0.75, 0)));
    EXPECT_NEAR(l->signedDistance(Vec3(0.75, 0.75, 0)), 0.25, 1e-6);
    EXPECT_NEAR(l->signedDistance(Vec3(0.25, 0.25, 0)), -0.25, 1e-6);
    const double dx = 0.02;
    // its edges on lattice lines: exact
    EXPECT_EQ(count(*l, Scalar(dx)), std::size_t(std::lround(0.75 / (dx * dx))));
    EXPECT_EQ(count(*reversed, Scalar(dx)), count(*l, Scalar(dx)));
    // a 1:20 beach: the triangle (0 0) (2 0) (2 0.1), area 0.1
    const auto beach = shape("type polygon; points ((0 0 0) (2 0 0) (2 0.1 0));", 2);
    expectMeasure(double(count(*beach, Scalar(0.005))) * 0.005 * 0.005, 0.1, 4.1, 0.005, "beach");
    EXPECT_TRUE(beach->contains(Vec3(1.5, 0.07, 0)));
    EXPECT_FALSE(beach->contains(Vec3(1.5, 0.08, 0)));
}

TEST(Shape, BadPolygonsAndShapesAreRefused) {
    EXPECT_NE(errorOf([] { shape("type polygon; points ((0 0 0) (2 1 0) (2 0 0) (0 2 0));", 2); })
                  .find("error: the polygon crosses itself: edge 0 (point 0 to 1) meets edge 2 (point 2 to 3)"),
              std::string::npos);
    EXPECT_NE(errorOf([] { shape("type polygon; points ((0 0 0) (1 1 0) (2 2 0));", 2); }).find("encloses no area"),
              std::string::npos);
    EXPECT_NE(errorOf([] { shape("type polygon; points ((0 0 0) (1 1 0));", 2); }).find("at least 3"),
              std::string::npos);
    EXPECT_NE(errorOf([] { shape("type polygon; points ((0 0 0) (1 1 0) (1 0 0));", 3); }).find("2D only"),
              std::string::npos);
    EXPECT_NE(errorOf([] { shape("type cylinder; centre (0 0 0); radius -1;", 2); })
                  .find("'radius' must be a positive number (keyword 'radius')"),
              std::string::npos);
    EXPECT_NE(errorOf([] { shape("type cylinder; point1 (0 0 0); point2 (0 0 0); radius 1;", 3); })
                  .find("must differ"),
              std::string::npos);
    EXPECT_NE(errorOf([] { shape("type cone; centre (0 0 0);", 2); }).find("valid: (box cylinder sphere polygon mesh)"),
              std::string::npos);
}

TEST(Shape, SubtractionCutsAHole) {
    const auto s = shape("type box; min (0 0 0); max (1 0.5 0); subtract { hole { type cylinder; centre (0.5 0.25 0); "
                         "radius 0.2; } }",
                         2);
    EXPECT_FALSE(s->contains(Vec3(0.5, 0.25, 0)));
    EXPECT_TRUE(s->contains(Vec3(0.1, 0.1, 0)));
    const double dx = 0.01;
    std::vector<Vec3> p;
    sampleShape(*s, Scalar(dx), 0, p);
    for (const Vec3& x : p) ASSERT_GE((x - Vec3(0.5, 0.25, 0)).norm(), 0.2 - 1e-6);
    expectMeasure(double(p.size()) * dx * dx, 0.5 - pi * 0.04, 2 * pi * 0.2, dx, "box less a circle");
}

TEST(Shape, BoxSamplesAsEver) {
    // a box off the origin's lattice keeps its own: min + (i + ½)Δx, round(size/Δx) cells
    const auto b = shape("type box; min (0.003 0.001 0); max (0.2 0.3 0);", 2);
    std::vector<Vec3> p;
    sampleShape(*b, Scalar(0.01), 0, p);
    ASSERT_EQ(p.size(), std::size_t(20 * 30));
    EXPECT_NEAR(p.front()[0], 0.008, 1e-6);
    EXPECT_NEAR(p.back()[1], 0.001 + 29.5 * 0.01, 1e-6);
    std::vector<Vec3> layers;
    sampleShape(*b, Scalar(0.01), Scalar(0.03), layers);
    EXPECT_EQ(layers.size(), std::size_t(20 * 30 - 14 * 24));
}

TEST(Shape, OverlappingRegionsAreFilledOnce) {
    log::setQuiet(true);
    const SampledGeometry g = sample("fluid { a { type cylinder; centre (0 0 0); radius 0.3; } "
                                     "b { type cylinder; centre (0.2 0 0); radius 0.3; } "
                                     "c { type box; min (-0.5 -0.1 0); max (0.5 0.1 0); } }",
                                     Scalar(0.02), 2);
    log::setQuiet(false);
    std::size_t lattice = 0; // the union's points on the case lattice
    for (int i = -40; i < 40; ++i)
        for (int j = -40; j < 40; ++j) {
            const Vec3 p((i + 0.5) * 0.02, (j + 0.5) * 0.02, 0);
            lattice += p.norm() < 0.3 || (p - Vec3(0.2, 0, 0)).norm() < 0.3 ||
                       (std::abs(p[0]) < 0.5 && std::abs(p[1]) < 0.1);
        }
    EXPECT_EQ(g.fluidPositions.size(), lattice);
    for (std::size_t i = 0; i < g.fluidPositions.size(); ++i)
        for (std::size_t k = i + 1; k < g.fluidPositions.size(); ++k)
            ASSERT_GE((g.fluidPositions[i] - g.fluidPositions[k]).norm(), 0.999 * 0.02) << i << " " << k;
    ASSERT_EQ(g.fluidBlocks.size(), 3u);
    EXPECT_EQ(g.fluidBlocks[0].count + g.fluidBlocks[1].count + g.fluidBlocks[2].count, lattice);
}

TEST(Shape, CurvedWallsAndBodies) {
    log::setQuiet(true);
    // water in a tank around a round pillar (a solid wall) and a floating disc (a body)
    const SampledGeometry g =
        sample("fluid { water { type box; min (0 0 0); max (1 0.5 0); } } "
               "walls { tank { type container; min (0 0 0); max (1 1 0); } "
               "        pillar { type cylinder; centre (0.3 0.2 0); radius 0.1; layers 3; } } "
               "bodies { disc { type cylinder; centre (0.7 0.4 0); radius 0.08; density 500; } }",
               Scalar(0.01), 2);
    log::setQuiet(false);
    ASSERT_EQ(g.walls.size(), 3u);
    const SampledWall& pillar = g.walls[1];
    const SampledWall& disc = g.walls[2];
    for (const Vec3& p : pillar.positions) {
        const double r = (p - Vec3(0.3, 0.2, 0)).norm();
        ASSERT_TRUE(r < 0.1 && r > 0.1 - 0.03 - 1e-9) << "the 3 outermost layers inside its surface: r " << r;
    }
    // ring of 3 spacings: π (0.1² − 0.07²)
    expectMeasure(double(pillar.positions.size()) * 1e-4, pi * (0.01 - 0.0049), 2 * pi * 0.17, 0.01, "pillar ring");
    // the water outside both, no particle nearer one of theirs than Δx, and filling the lattice up
    // to them: its area is the box's less the two circles' to a fraction of a spacing along their
    // perimeters (−0.0009 m²; a clearance of half a spacing from the surfaces, the rule before,
    // left the lattice points within it empty: −0.0033 m²)
    for (const Vec3& p : g.fluidPositions) {
        ASSERT_GT((p - Vec3(0.3, 0.2, 0)).norm(), 0.1) << "fluid outside the pillar";
        ASSERT_GT((p - Vec3(0.7, 0.4, 0)).norm(), 0.08) << "fluid outside the disc";
        for (const SampledWall* solid : {&pillar, &disc})
            for (const Vec3& q : solid->positions) ASSERT_GE((p - q).norm(), 0.999 * 0.01) << solid->name;
    }
    const double water = 0.5 - pi * 0.01 - pi * 0.0064, perimeters = 2 * pi * (0.1 + 0.08);
    EXPECT_NEAR(double(g.fluidPositions.size()) * 1e-4, water, 0.15 * perimeters * 0.01) << "the water's area";
    EXPECT_TRUE(pillar.occupies(Vec3(0.3, 0.2, 0), 2));
    EXPECT_FALSE(pillar.occupies(Vec3(0.3, 0.31, 0), 2));
    // the disc's mass and inertia from its shape: ρ π r², ρ π r⁴ / 2
    EXPECT_NEAR(disc.mass.volume, pi * 0.0064, 0.5 * 2 * pi * 0.08 * 0.01);
    // its inertia is that of its lattice points: a uniform disc's, V r²/2, with r of the lattice's
    // area (r = 8 Δx: the lattice's disc is 1.7 % wider than the circle, its Izz 7 % larger)
    const double r2 = disc.mass.volume / pi;
    EXPECT_NEAR(disc.mass.inertia(2, 2), disc.mass.volume * r2 / 2, 0.01 * disc.mass.volume * r2 / 2);
    EXPECT_NEAR(disc.mass.centroid[0], 0.7, 1e-6);
    EXPECT_NEAR(disc.mass.centroid[1], 0.4, 1e-6);
}

TEST(Shape, WallBoxOffTheLatticeIsRefusedUnlessSnapped) {
    const std::string tank = "fluid { water { type box; min (0 0 0); max (0.2 0.2 0); } }\n"
                             "walls { tank { type container; min (0 0 0);\n max (0.205 0.3 0); ";
    const std::string e = errorOf([&] { sample(tank + "} }", Scalar(0.01), 2); });
    EXPECT_NE(e.find("geometry:3:2: error: walls.tank: size along x (0.205) is not a multiple of particleSpacing "
                     "0.01; the nearest valid max x are 0.2 and 0.21 (or add 'snapToLattice yes;'"),
              std::string::npos)
        << e;
    EXPECT_NE(e.find("(keyword 'max')"), std::string::npos) << e;
    log::setQuiet(true);
    const SampledGeometry g = sample(tank + "snapToLattice yes; } }", Scalar(0.01), 2);
    log::setQuiet(false);
    EXPECT_NEAR(g.walls[0].max[0], 0.21, 1e-6);
    // a solid box as well
    EXPECT_NE(errorOf([] {
                  sample("fluid { water { type box; min (0 0 0); max (0.2 0.2 0); } }\n"
                         "walls { block { type box; min (0.5 0 0); max (0.525 0.1 0); } }",
                         Scalar(0.01), 2);
              }).find("walls.block: size along x (0.025)"),
              std::string::npos);
}

TEST(Shape, InitialFieldsFromExpressions) {
    const SampledGeometry g = sample("fluid { drop { type cylinder; centre (0 0 0); radius 1; "
                                     "velocity (\"-100*x\" \"100*y\" 0); initialPressure \"5e6*(1 - x^2 - y^2)\"; } }",
                                     Scalar(0.1), 2);
    ASSERT_FALSE(g.fluidPositions.empty());
    for (std::size_t i = 0; i < g.fluidPositions.size(); ++i) {
        const Vec3& p = g.fluidPositions[i];
        EXPECT_NEAR(g.fluidVelocities[i][0], -100 * p[0], 1e-3);
        EXPECT_NEAR(g.fluidVelocities[i][1], 100 * p[1], 1e-3);
        EXPECT_EQ(g.fluidVelocities[i][2], 0);
        EXPECT_NEAR(g.fluidPressures[i], 5e6 * (1 - p.squaredNorm()), 5);
    }
    const std::string bad = errorOf([] {
        sample("fluid { drop { type cylinder; centre (0 0 0); radius 1;\n velocity (\"-100*x\" \"100*(y\" 0); } }",
               Scalar(0.1), 2);
    });
    EXPECT_NE(bad.find("geometry:2:21: error: expression \"100*(y\" of 'velocity': "), std::string::npos) << bad;
    EXPECT_NE(bad.find("(muParser"), std::string::npos) << bad;
    const std::string unknown = errorOf([] { Expression("2*w", {"geometry", 4, 9}, "initialPressure"); });
    EXPECT_NE(unknown.find("geometry:4:9: error: expression \"2*w\" of 'initialPressure': "), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("\"w\""), std::string::npos) << unknown;
    const std::string notFinite = errorOf([] { Expression("sqrt(x)", {"geometry", 4, 9}, "initialPressure")(Vec3(-1, 0, 0)); });
    EXPECT_NE(notFinite.find("must be finite"), std::string::npos) << notFinite;
}

TEST(Shape, WaterUnderASubmergedSolidStartsAsDeepAsTheWaterAboveIt) {
    // a round pillar and a polygon rock under 0.5 m of water: every particle starts at
    // p = ρ0 g (H − y), H = 0.5 (before, the water under a solid took its depth from its underside)
    log::setQuiet(true);
    const SampledGeometry g = sampleGeometry(
        Dictionary::fromString("fluid { water { type box; min (0 0 0); max (1 0.5 0); initialPressure hydrostatic; } } "
                               "walls { tank { type container; min (0 0 0); max (1 1 0); } "
                               "        pillar { type cylinder; centre (0.3 0.2 0); radius 0.1; } "
                               "        rock { type polygon; points ((0.6 0.1 0) (0.9 0.1 0) (0.75 0.3 0)); } }",
                               "geometry"),
        Scalar(0.01), 2, Vec3(0, -9.81, 0));
    log::setQuiet(false);
    std::size_t under = 0;
    for (std::size_t i = 0; i < g.fluidPositions.size(); ++i) {
        const Vec3& p = g.fluidPositions[i];
        ASSERT_NEAR(g.fluidDepths[i], 0.5 - p[1], 1e-5) << "at (" << p[0] << " " << p[1] << ")";
        under += (std::abs(p[0] - 0.3) < 0.05 && p[1] < 0.1) || (std::abs(p[0] - 0.75) < 0.05 && p[1] < 0.1);
    }
    EXPECT_GT(under, 50u) << "water under the solids";
}
