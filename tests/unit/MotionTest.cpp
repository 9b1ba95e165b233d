// Prescribed wall motions as rigid transforms (Motion.hpp): velocities and accelerations equal
// finite differences of the positions, rotations keep the wall rigid, and the wave makers' stroke
// follows Biesel's first-order transfer functions (their published shallow- and deep-water limits).
#include "Motion.hpp"
#include "TestSupport.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

using namespace spindrift;
using V3 = Eigen::Vector3d;

namespace {

MotionContext context(int dim, const std::filesystem::path& caseDir = {}) {
    MotionContext c;
    c.dimension = dim;
    c.runStart = 0;
    c.runEnd = 20;
    c.caseDir = caseDir;
    c.gravity = dim == 2 ? V3(0, -9.81, 0) : V3(0, 0, -9.81);
    return c;
}

std::unique_ptr<Motion> motionOf(const std::string& text, const MotionContext& c) {
    return Motion::read(Dictionary::fromString(text, "geometry"), c);
}

std::string errorOf(const std::string& text, const MotionContext& c) {
    try {
        motionOf(text, c);
    } catch (const InputError& e) {
        return e.what();
    }
    return "<no error>";
}

// velocity and acceleration of points of the wall against central differences of their positions
void expectDerivativesMatchPositions(const Motion& m, int dim, const std::vector<double>& times, const std::string& what) {
    const double z = dim == 3 ? 0.25 : 0.0;
    const std::vector<V3> points{V3(0.3, 0.1, z), V3(-0.2, 0.7, -z), V3(1.1, -0.4, 2 * z)};
    const double h = 1e-4;
    for (double t : times)
        for (const V3& x0 : points) {
            const V3 xm = m.position(m.state(t - h), x0), x = m.position(m.state(t), x0), xp = m.position(m.state(t + h), x0);
            const V3 vfd = (xp - xm) / (2 * h), afd = (xp - 2 * x + xm) / (h * h);
            const RigidState s = m.state(t);
            const V3 v = m.velocityAt(s, x), a = m.accelerationAt(s, x);
            const double vScale = std::max(1.0, v.norm()), aScale = std::max(1.0, a.norm());
            EXPECT_LT((v - vfd).norm(), 1e-6 * vScale) << what << " at t = " << t << ": v " << v.transpose()
                                                         << ", finite difference " << vfd.transpose();
            EXPECT_LT((a - afd).norm(), 1e-3 * aScale) << what << " at t = " << t << ": a " << a.transpose()
                                                         << ", finite difference " << afd.transpose();
            // the drawn position is recovered by the inverse transform
            EXPECT_LT((m.drawnPosition(s, x) - x0).norm(), 1e-12) << what;
        }
}

} // namespace

TEST(Motion, VelocityAndAccelerationAreTheDerivativesOfThePositions) {
    test::TempDir tmp;
    std::ofstream(tmp.path() / "roll.dat") << "# t dx dy dz angle\n0 0 0 0 0\n0.5 0.02 0.01 0 3\n1.0 0.05 -0.02 0 -4\n"
                                              "1.7 0.01 0.0 0 6\n2.5 0 0 0 0\n";
    std::ofstream(tmp.path() / "roll3.dat") << "0 0 0 0 0\n0.5 0.02 0.01 0.03 3\n1.0 0.05 -0.02 0.01 -4\n2 0 0 0 1\n";
    const std::vector<double> times{0.3, 0.77, 1.31, 2.2, 3.9, 7.45};
    const std::vector<std::pair<std::string, int>> cases{
        {"type linear; velocity (0.5 0.1 0); startTime 0.1; endTime 5;", 2},
        {"type oscillating; direction (1 1 0); amplitude 0.05; period 1.3; phase 0.4; startTime 0.2;", 2},
        {"type rotating; centre (0.4 0.2 0); rate 1.7; rampTime 1;", 2},
        {"type rotating; axis (1 2 3); centre (0.4 0.2 0.1); rate -0.9;", 3},
        {"type rolling; centre (0.5 0.5 0); amplitude 8; period 1.5; phase 0.3; rampTime 0.9;", 2},
        {"type rolling; axis (1 0 0); centre (0.5 0.5 0.5); amplitude 10; period 2;", 3},
        {"type flap; hinge (0 0 0); amplitude 12; period 1.1;", 2},
        {"type pistonWaveMaker; waveHeight 0.1; period 1.4; depth 0.55; rampTime 2;", 2},
        {"type pistonWaveMaker; waveHeight 0.1; period 1.4; depth 0.55; rampTime 2; secondOrder yes;", 2},
        {"type flapWaveMaker; waveHeight 0.08; period 1.2; depth 0.5; hinge (0 0 0); rampTime 2;", 2},
        {"type flapWaveMaker; waveHeight 0.08; period 1.2; depth 0.5; hinge (0 0 0); direction (0 1 0);", 3},
        {"type table; file \"roll.dat\"; centre (0.5 0.3 0); interpolation spline;", 2},
        {"type table; file \"roll3.dat\"; axis (0 1 1); centre (0.5 0.3 0.2); interpolation spline;", 3},
    };
    for (const auto& [text, dim] : cases) {
        const auto m = motionOf(text, context(dim, tmp.path()));
        expectDerivativesMatchPositions(*m, dim, times, text);
    }
    // linear interpolation: piecewise linear (velocity the slope, no acceleration inside an interval)
    const auto table = motionOf("type table; file \"roll.dat\"; centre (0.5 0.3 0);", context(2, tmp.path()));
    expectDerivativesMatchPositions(*table, 2, {0.2, 0.7, 1.3, 2.1}, "linear table");
    const RigidState s = table->state(0.75); // halfway between rows 0.5 and 1.0
    EXPECT_NEAR(s.translation[0], 0.035, 1e-12);
    EXPECT_NEAR(Eigen::AngleAxisd(s.rotation).angle() * 180 / std::numbers::pi, 0.5, 1e-9);
    // held beyond the table
    EXPECT_NEAR(table->state(10).translation.norm(), 0, 1e-15);
}

TEST(Motion, EveryMotionIsAtRestInItsDrawnPoseBeforeItsStart) {
    const std::vector<std::string> texts{
        "type rotating; centre (0.4 0.2 0); rate 1.7; startTime 0.5;",
        "type rolling; centre (0.5 0.5 0); amplitude 8; period 1.5; phase 0.3; startTime 0.5;",
        "type pistonWaveMaker; waveHeight 0.1; period 1.4; depth 0.55; startTime 0.5;",
        "type flapWaveMaker; waveHeight 0.08; period 1.2; depth 0.5; hinge (0 0 0); startTime 0.5;"};
    for (const std::string& text : texts) {
        const auto m = motionOf(text, context(2));
        for (double t : {0.0, 0.25, 0.5}) { // in its drawn pose up to its start (velocity may jump there)
            const RigidState s = m->state(t);
            EXPECT_EQ(s.translation, V3::Zero()) << text;
            EXPECT_NEAR((s.rotation - Eigen::Matrix3d::Identity()).norm(), 0, 1e-15) << text;
            if (t < 0.5) {
                EXPECT_EQ(s.velocity.norm() + s.omega.norm(), 0) << text;
            }
        }
        // ramped wave makers also start without a jump in velocity or acceleration
        if (text.find("WaveMaker") != std::string::npos) {
            const RigidState s = m->state(0.5 + 1e-6);
            EXPECT_LT(s.velocity.norm() + s.omega.norm(), 1e-6) << text;
        }
    }
}

TEST(Motion, ARotatingWallStaysRigid) {
    // particles of a wall keep their distances under rotation about any axis (3D) and roll (2D)
    std::vector<V3> wall;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 5; ++j) wall.emplace_back(0.1 * i - 0.2, 0.05 * j, 0.03 * ((i + j) % 3));
    for (const auto& [text, dim] : std::vector<std::pair<std::string, int>>{
             {"type rotating; axis (1 2 3); centre (0.4 0.2 0.1); rate 2.3;", 3},
             {"type rolling; axis (0 1 0); centre (0.1 0.1 0.1); amplitude 30; period 1;", 3}}) {
        const auto m = motionOf(text, context(dim));
        for (double t : {0.37, 1.9, 13.2}) {
            const RigidState s = m->state(t);
            EXPECT_NEAR(s.rotation.determinant(), 1, 1e-12);
            double worst = 0, moved = 0;
            for (std::size_t a = 0; a < wall.size(); ++a) {
                const V3 xa = m->position(s, wall[a]);
                moved = std::max(moved, (xa - wall[a]).norm());
                for (std::size_t b = a + 1; b < wall.size(); ++b)
                    worst = std::max(worst, std::abs((xa - m->position(s, wall[b])).norm() - (wall[a] - wall[b]).norm()));
            }
            EXPECT_LT(worst, 1e-12) << text << " at t = " << t;
            EXPECT_GT(moved, 0.01) << text << " did not move at t = " << t; // it is a motion
        }
    }
}

TEST(Motion, TheSweptRangeBoundsARotatingWall) {
    const auto m = motionOf("type rotating; centre (0 0 0); rate 1;", context(2));
    Vec3 lo, hi;
    // a plate from x = 1 to 2 along the x axis, swept a full turn: the disc of radius 2
    m->sweptRange(0, 2 * std::numbers::pi, Vec3(1, 0, 0), Vec3(2, 0, 0), lo, hi);
    for (int a = 0; a < 2; ++a) {
        EXPECT_LE(lo[a], -2 + 1e-9);
        EXPECT_GE(hi[a], 2 - 1e-9);
        EXPECT_GT(lo[a], -2.1);
        EXPECT_LT(hi[a], 2.1);
    }
}

TEST(Motion, BieselTransferFunctionsHaveTheirPublishedLimits) {
    // Dean & Dalrymple (1991) eqs. 6.22-6.23: in shallow water H/S -> kd (piston), kd/2 (flap);
    // in deep water both -> 2
    for (double kd : {1e-3, 1e-2}) {
        EXPECT_NEAR(waveMaker::pistonRatio(kd) / kd, 1, kd * kd);
        EXPECT_NEAR(waveMaker::flapRatio(kd) / (kd / 2), 1, kd * kd);
    }
    EXPECT_NEAR(waveMaker::pistonRatio(20), 2, 1e-6);
    EXPECT_NEAR(waveMaker::flapRatio(20), 2, 0.15); // 2 (1 - 1/kd) for large kd
    EXPECT_NEAR(waveMaker::flapRatio(200), 2, 0.015);
    // a piston makes a higher wave than a flap of the same stroke at the surface, at every depth
    for (double kd : {0.1, 0.5, 1.0, 2.0, 5.0}) EXPECT_GT(waveMaker::pistonRatio(kd), waveMaker::flapRatio(kd));
    // the dispersion relation: ω² = g k tanh(kd); shallow water k = ω/√(gd), deep water k = ω²/g
    const double g = 9.81;
    for (double T : {0.5, 1.2, 1.6, 10.0}) {
        const double omega = 2 * std::numbers::pi / T, d = 0.55;
        const double k = waveMaker::waveNumber(omega, d, g);
        EXPECT_NEAR(g * k * std::tanh(k * d), omega * omega, 1e-12 * omega * omega);
    }
    EXPECT_NEAR(waveMaker::waveNumber(0.01, 0.5, g), 0.01 / std::sqrt(g * 0.5), 1e-6 * 0.01 / std::sqrt(g * 0.5));
    EXPECT_NEAR(waveMaker::waveNumber(30, 10, g), 900 / g, 1e-9);
    // the piston's stroke over a period after its ramp: its first harmonic is S/2 = H/(2 H/S)
    const auto m = motionOf("type pistonWaveMaker; waveHeight 0.1; period 1.4; depth 0.55; rampTime 2;", context(2));
    const double T = 1.4, omega = 2 * std::numbers::pi / T, k = waveMaker::waveNumber(omega, 0.55, g);
    double b1 = 0;
    const int n = 1000;
    for (int i = 0; i < n; ++i) {
        const double t = 3 * T + T * i / n;
        b1 += 2.0 / n * m->state(t).translation[0] * std::sin(omega * t);
    }
    EXPECT_NEAR(b1, 0.1 / waveMaker::pistonRatio(k * 0.55) / 2, 1e-6);
}

TEST(Motion, BadMotionsAreRefusedAtTheirKeyword) {
    const auto c2 = context(2);
    EXPECT_NE(errorOf("type flapWaveMaker; waveHeight 0.08; period 1.2; depth 0.5; hinge (0 0 0);\nsecondOrder yes;", c2)
                  .find("geometry:2:1: error: flapWaveMaker is first order only"),
              std::string::npos);
    EXPECT_NE(errorOf("type rolling; axis (1 0 0); centre (0 0 0); amplitude 5; period 1;", c2).find("axis must be (0 0 1)"),
              std::string::npos);
    EXPECT_NE(errorOf("type pistonWaveMaker; waveHeight 0.5; period 1.4; depth 0.55;", c2).find("would break"),
              std::string::npos);
    EXPECT_NE(errorOf("type pistonWaveMaker; waveHeight 0.1; period 1.4; depth -1;", c2).find("(keyword 'depth')"),
              std::string::npos);
    EXPECT_NE(errorOf("type pistonWaveMaker; waveHeight 0.1; period 1.4; depth 0.5; direction (0 1 0);", c2)
                  .find("normal to gravity"),
              std::string::npos);
    test::TempDir tmp;
    std::ofstream(tmp.path() / "bad.dat") << "0 0 0 0 0\n# a comment\n1 0 0 0 5\n0.5 0 0 0 1\n";
    std::ofstream(tmp.path() / "short.dat") << "0 0 0 0 0\n1 0 0 0\n";
    const auto c = context(2, tmp.path());
    const std::string bad = errorOf("type table; file \"bad.dat\";", c);
    EXPECT_NE(bad.find("bad.dat:4: error: the motion table's times must increase: 0.5 follows 1"), std::string::npos) << bad;
    const std::string shortRow = errorOf("type table; file \"short.dat\";", c);
    EXPECT_NE(shortRow.find("short.dat:2: error: a row of the motion table must hold 5 numbers"), std::string::npos)
        << shortRow;
    EXPECT_NE(errorOf("type table; file \"missing.dat\";", c).find("cannot open the motion table"), std::string::npos);
    EXPECT_NE(errorOf("type table; file \"bad.dat\"; interpolation cubic;", c).find("interpolation"), std::string::npos);
}
