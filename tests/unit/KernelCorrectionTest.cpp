// The kernel gradient correction (libsrc/KernelCorrection.hpp; wcsph `gradientCorrection yes`):
// the pressure gradient of a linear field exact inside a lattice where the plain one is short
// (a column at rest carried 98.8 % of gravity), the identity at a free surface, and the pair
// forces still equal and opposite, with a wall's reaction what the fluid felt from it.
#include "KernelCorrection.hpp"
#include "TestSupport.hpp"

#include <gtest/gtest.h>
#include <random>

using namespace spindrift;

namespace {

struct Block {
    Scene s;
    std::unique_ptr<Kernel> kernel;
    int n;
    double dx = 0.01;
    Block(int dim, int n_) : n(n_) {
        s.physics = test::physicsFor(dim, Scalar(dx), 2.6);
        kernel = test::createModel<Kernel>("type wendlandC2;", s.physics);
        test::fillLattice(s, *kernel, Vec3::Zero(), Vec3(n * dx, n * dx, dim == 3 ? n * dx : 0));
    }
    ParticleSystem& fluid() { return test::fluidOf(s); }
    // p = p0 + G·x at every particle, ρ = ρ0: q = p/ρ0²
    std::vector<Scalar> linearPressure(const Vec3& G, double p0) {
        std::vector<Scalar> q;
        const Scalar rho0 = s.physics.rho0;
        for (std::size_t i = 0; i < fluid().size(); ++i) {
            fluid().particles.density()[i] = rho0;
            fluid().particles.pressure()[i] = Scalar(p0 + G.dot(fluid().particles.position()[i]));
            q.push_back(fluid().particles.pressure()[i] / (rho0 * rho0));
        }
        return q;
    }
    // the particles two supports away from the block's faces (their neighbours' L are the lattice's)
    bool inside(std::size_t i) const {
        const Vec3& x = test::fluidOf(s).particles.position()[i];
        const double h = 2 * 2.6 * dx;
        for (int a = 0; a < s.physics.dimension; ++a)
            if (x[a] < h || x[a] > n * dx - h) return false;
        return true;
    }
};

TEST(KernelCorrection, LinearPressureGradientExactInsideALattice) {
    for (int dim : {2, 3}) {
        Block b(dim, dim == 2 ? 20 : 16);
        const Vec3 G = dim == 2 ? Vec3(3000, -9810, 0) : Vec3(3000, -9810, 1500); // Pa/m
        const std::vector<Scalar> q = b.linearPressure(G, 5000);
        std::vector<Mat3> L;
        kernelCorrectionMatrices(b.s, b.fluid(), b.fluid().particles.position(), L);
        auto& a = b.fluid().particles.acceleration();
        // the plain symmetric gradient: short by the lattice sum of the kernel's gradient moment
        for (auto& ai : a) ai.setZero();
        symmetricPressureAcceleration(b.s, b.fluid(), b.fluid().particles.position(), q.data(),
                                      [&](std::size_t i, const Vec3& ai) { a[i] += ai; });
        const Vec3 exact = -G / b.s.physics.rho0;
        double plainError = 0;
        int counted = 0;
        for (std::size_t i = 0; i < a.size(); ++i)
            if (b.inside(i)) {
                plainError = std::max(plainError, double((a[i] - exact).norm() / exact.norm()));
                ++counted;
            }
        ASSERT_GT(counted, 10);
        EXPECT_GT(plainError, 0.005) << dim << "D: the plain gradient is short on a lattice (the test is not vacuous)";
        for (auto& ai : a) ai.setZero();
        addCorrectedSymmetricPressureAcceleration(b.s, b.fluid(), q, L);
        std::size_t centre = 0;
        while (!b.inside(centre)) ++centre;
        for (std::size_t i = 0; i < a.size(); ++i) {
            if (!b.inside(i)) continue;
            // float: the pair sums of p ~ 5 kPa cancel to a gradient of 10 kPa/m over a 2.6 mm support
            EXPECT_NEAR((a[i] - exact).norm() / exact.norm(), 0.0, test::tol(1e-9, 1e-3)) << dim << "D, particle " << i;
            // L_i is the inverse transpose of the lattice's moment, the same everywhere inside
            EXPECT_NEAR((L[i] - L[centre]).norm(), 0.0, test::tol(1e-9, 1e-5));
        }
        std::cout << dim << "D: plain gradient off by " << 100 * plainError << " % inside the lattice, corrected exact\n";
    }
}

// At a corner of the block (a quarter of the support filled) the matrix is far from full rank:
// the correction gives way to the plain gradient (L = I).
TEST(KernelCorrection, IdentityAtAFreeSurfaceCorner) {
    Block b(2, 12);
    b.linearPressure(Vec3::Zero(), 0);
    std::vector<Mat3> L;
    kernelCorrectionMatrices(b.s, b.fluid(), b.fluid().particles.position(), L);
    std::size_t corner = 0;
    for (std::size_t i = 0; i < L.size(); ++i)
        if (b.fluid().particles.position()[i].norm() < b.fluid().particles.position()[corner].norm()) corner = i;
    Mat3 I = Mat3::Identity();
    I(2, 2) = 0;
    EXPECT_NEAR((L[corner] - I).norm(), 0.0, test::tol(1e-12, 1e-6));
}

// Jittered water over a floor of wall particles with their own pressure: the fluid's pair forces
// cancel, and the force the fluid feels from the floor is minus the floor's reported reaction.
TEST(KernelCorrection, PairForcesEqualAndOppositeAndTheWallReactionIsWhatTheFluidFelt) {
    Block b(2, 16);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    for (auto& x : b.fluid().particles.position()) x += 0.2 * b.dx * Vec3(u(rng), u(rng), 0);
    std::vector<Vec3> floor;
    for (int l = 0; l < 3; ++l)
        for (int i = -3; i < b.n + 3; ++i) floor.emplace_back((i + 0.5) * b.dx, -(l + 0.5) * b.dx, 0);
    ParticleSystem& wall = test::addWallSystem(b.s, "floor", floor);
    test::setWallMasses(b.s, b.fluid().particles.particleMass());
    wall.pressureMirrored = false;
    for (std::size_t k = 0; k < wall.size(); ++k) wall.particles.pressure()[k] = Scalar(2000 + 100 * u(rng));
    test::rebuild(b.s);
    const std::vector<Scalar> q = b.linearPressure(Vec3(0, -9810, 0), 1600);
    std::vector<Mat3> L;
    kernelCorrectionMatrices(b.s, b.fluid(), b.fluid().particles.position(), L);
    auto& a = b.fluid().particles.acceleration();
    for (auto& ai : a) ai.setZero();
    addCorrectedSymmetricPressureAcceleration(b.s, b.fluid(), q, L);
    Eigen::Vector3d total = Eigen::Vector3d::Zero();
    double scale = 0;
    for (const Vec3& ai : a) {
        total += double(b.fluid().particles.particleMass()) * ai.cast<double>();
        scale += double(b.fluid().particles.particleMass()) * ai.cast<double>().norm();
    }
    Reactions reactions;
    reactions.want(wall.index);
    reactions.clear();
    addCorrectedSymmetricPressureReactions(b.s, b.fluid(), q, L, reactions);
    const Eigen::Vector3d onWall = reactions.total(wall.index).force;
    ASSERT_GT(onWall.norm(), 0.01 * scale) << "the floor takes a real share (the test is not vacuous)";
    // Σ m a over the fluid is the floor's force on it (fluid pairs cancel), minus the reaction
    EXPECT_NEAR((total + onWall).norm(), 0.0, test::tol(1e-10, 1e-4) * scale);
}

} // namespace
