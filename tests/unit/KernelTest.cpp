// Kernels (plugins/kernels/*) and the KernelTable: normalisation, derivatives, compact support,
// and the table against the analytic kernel.
#include "KernelTable.hpp"
#include "TestSupport.hpp"

#include <gtest/gtest.h>
#include <cmath>
#include <numbers>

using namespace spindrift;

namespace {

struct KernelCase {
    std::string name;
    int dim;
};

std::string caseName(const testing::TestParamInfo<KernelCase>& info) {
    return info.param.name + std::to_string(info.param.dim) + "D";
}

// ∫ W dV over the support: Gauss–Legendre (5 points) on 4096 equal intervals of [0, h], whose
// nodes include q = 1/2 (where piecewise kernels change formula).
double integral(const Kernel& k) {
    static const double x[5] = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640, 0.9061798459386640};
    static const double w[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665, 0.2369268850561891, 0.2369268850561891};
    const int n = 4096;
    const double h = k.supportRadius(), dr = h / n;
    double sum = 0;
    for (int i = 0; i < n; ++i)
        for (int g = 0; g < 5; ++g) {
            const double r = (i + 0.5) * dr + 0.5 * dr * x[g];
            const double shell = k.dimension() == 2 ? 2 * std::numbers::pi * r : 4 * std::numbers::pi * r * r;
            sum += w[g] * 0.5 * dr * k.W(r) * shell;
        }
    return sum;
}

class KernelTest : public testing::TestWithParam<KernelCase> {
protected:
    std::unique_ptr<Kernel> make(double h = 0.026) {
        auto physics = test::physicsFor(GetParam().dim, h / 2.6, 2.6);
        return test::createModel<Kernel>("type " + GetParam().name + ";", physics);
    }
};

TEST_P(KernelTest, IntegratesToOne) {
    for (double h : {0.026, 1.0, 3.5}) {
        auto k = make(h);
        EXPECT_NEAR(integral(*k), 1.0, 1e-6) << "h = " << h;
    }
}

TEST_P(KernelTest, VanishesAtAndBeyondSupport) {
    auto k = make();
    const double h = k->supportRadius();
    EXPECT_NEAR(k->W(h), 0.0, 1e-12 * k->W(0));
    EXPECT_EQ(k->W(1.01 * h), 0.0);
    EXPECT_EQ(k->dWdr(1.01 * h), 0.0);
    EXPECT_NEAR(k->dWdr(0.0), 0.0, 1e-9 * std::abs(k->W(0)) / h) << "gradient must vanish at r = 0";
    EXPECT_GT(k->W(0), 0.0);
    for (double q = 0.05; q < 1; q += 0.05) EXPECT_LE(k->dWdr(q * h), 0.0) << "W must decrease, q = " << q;
}

TEST_P(KernelTest, GradientMatchesFiniteDifference) {
    auto k = make();
    if (!k->gradientIsDerivativeOfW()) GTEST_SKIP() << "gradient shape differs from W by design";
    const double h = k->supportRadius(), e = 1e-6 * h;
    double worst = 0, scale = 0;
    for (double q = 0.01; q < 0.995; q += 0.0123) {
        const double r = q * h;
        const double fd = (k->W(r + e) - k->W(r - e)) / (2 * e);
        worst = std::max(worst, std::abs(fd - k->dWdr(r)));
        scale = std::max(scale, std::abs(k->dWdr(r)));
    }
    EXPECT_LT(worst / scale, 1e-6);
}

TEST_P(KernelTest, LaplacianMatchesFiniteDifference) {
    auto k = make();
    if (!k->gradientIsDerivativeOfW()) GTEST_SKIP() << "laplacian shape differs from W by design";
    const double h = k->supportRadius(), e = 1e-4 * h;
    const int d = k->dimension();
    double worst = 0, scale = 0;
    for (double q = 0.02; q < 0.99; q += 0.0173) {
        const double r = q * h;
        const double second = (k->W(r + e) - 2 * k->W(r) + k->W(r - e)) / (e * e);
        const double lap = second + (d - 1) * k->dWdr(r) / r;
        worst = std::max(worst, std::abs(lap - k->laplacian(r)));
        scale = std::max(scale, std::abs(k->laplacian(r)));
    }
    EXPECT_LT(worst / scale, 1e-5);
}

// The table reproduces W, dW/dr and ∇²W to 1e-6 relative to the largest value of each
// (the relative error is taken against the maximum because W → 0 at the support).
TEST_P(KernelTest, TableMatchesAnalyticKernel) {
    auto k = make();
    KernelTable table(*k);
    table.enableLaplacian();
    const double h = k->supportRadius();
    double errW = 0, errD = 0, errL = 0, maxW = 0, maxD = 0, maxL = 0;
    for (int i = 0; i <= 100000; ++i) {
        const double r = h * i / 100000.0 * 0.999999;
        errW = std::max(errW, std::abs(table.W(r) - k->W(r)));
        errD = std::max(errD, std::abs(table.dWdr(r) - k->dWdr(r)));
        errL = std::max(errL, std::abs(table.laplacian(r) - k->laplacian(r)));
        maxW = std::max(maxW, std::abs(k->W(r)));
        maxD = std::max(maxD, std::abs(k->dWdr(r)));
        maxL = std::max(maxL, std::abs(k->laplacian(r)));
    }
    EXPECT_LT(errW / maxW, 1e-6);
    EXPECT_LT(errD / maxD, 1e-6);
    EXPECT_LT(errL / maxL, 1e-6);
    EXPECT_EQ(table.W(h), 0.0);
    EXPECT_EQ(table.W(2 * h), 0.0);
    EXPECT_DOUBLE_EQ(table.W0(), k->W(0));
    // gradient direction: points from j to i times dW/dr (< 0): towards j
    const Vec3 rij(0.3 * h, 0.1 * h, 0);
    const Vec3 g = table.gradW(rij);
    EXPECT_LT(g.dot(rij), 0.0);
    EXPECT_EQ(table.gradW(Vec3::Zero()), Vec3::Zero());
}

INSTANTIATE_TEST_SUITE_P(Kernels, KernelTest,
                         testing::Values(KernelCase{"cubicSpline", 2}, KernelCase{"cubicSpline", 3},
                                         KernelCase{"wendlandC2", 2}, KernelCase{"wendlandC2", 3}),
                         caseName);

} // namespace
