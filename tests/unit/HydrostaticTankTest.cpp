// End to end: the hydrostaticTank2D tutorial (copied, run in-process) settles to
// p = ρ0 g (H − z) and keeps every particle in the tank.
#include "Case.hpp"
#include "Log.hpp"
#include "Simulation.hpp"
#include "TestSupport.hpp"

#include <gtest/gtest.h>

using namespace spindrift;
namespace fs = std::filesystem;

namespace {

fs::path copyTutorial(const std::string& name, const fs::path& into) {
    const fs::path target = into / name;
    copyCaseInput(fs::path(SPINDRIFT_SOURCE_DIR) / "tutorials" / name, target);
    return target;
}

TEST(HydrostaticTank2D, SettlesToHydrostaticPressure) {
    log::setQuiet(true);
    test::TempDir tmp;
    const fs::path caseDir = copyTutorial("hydrostaticTank2D", tmp.path());
    Simulation sim(caseDir);
    const RunSummary r = sim.run();
    EXPECT_GT(r.steps, 100);

    const auto& s = sim.scene();
    const double dx = s.physics.particleSpacing, rho0 = s.physics.rho0, g = 9.81, H = 0.3, width = 0.2;
    // every particle stays inside the tank
    for (const auto& x : test::fluidOf(s).particles.position()) {
        ASSERT_GE(x.x(), 0.0);
        ASSERT_LE(x.x(), width);
        ASSERT_GE(x.y(), 0.0);
        ASSERT_LE(x.y(), H + 2 * dx);
    }
    // pressure against ρ0 g (H − z), averaged over the bottom row and over a mid-depth row
    auto rowPressure = [&](double zLo, double zHi, double& zMean) {
        double p = 0;
        int n = 0;
        zMean = 0;
        for (std::size_t i = 0; i < test::fluidOf(s).particles.size(); ++i) {
            const double z = test::fluidOf(s).particles.position()[i].y();
            if (z >= zLo && z < zHi) {
                p += test::fluidOf(s).particles.pressure()[i];
                zMean += z;
                ++n;
            }
        }
        zMean /= n;
        return p / n;
    };
    double zBottom, zMid;
    const double pBottom = rowPressure(0, dx, zBottom);
    const double pMid = rowPressure(0.15 - 0.5 * dx, 0.15 + 0.5 * dx, zMid);
    const double bottomError = std::abs(pBottom - rho0 * g * (H - zBottom)) / (rho0 * g * H);
    const double midError = std::abs(pMid - rho0 * g * (H - zMid)) / (rho0 * g * H);
    double vMax = 0;
    for (const auto& v : test::fluidOf(s).particles.velocity()) vMax = std::max(vMax, double(v.norm()));
    std::cout << "hydrostaticTank2D: " << test::fluidOf(s).particles.size() << " particles, " << r.steps << " steps; bottom pressure "
              << pBottom << " Pa vs " << rho0 * g * (H - zBottom) << " Pa (error " << 100 * bottomError
              << " % of rho0 g H), mid-depth error " << 100 * midError << " %, max speed " << vMax << " m/s\n";
    EXPECT_LT(bottomError, 0.05);
    EXPECT_LT(midError, 0.05);
    EXPECT_LT(vMax, 0.1); // residual sloshing, < 6 % of sqrt(g H)
    // the run wrote its time directories and a collection
    EXPECT_TRUE(fs::exists(caseDir / "0" / "fluid.vtp"));
    EXPECT_TRUE(fs::exists(caseDir / "0" / "tank.vtp")); // the wall system "tank"
    EXPECT_TRUE(fs::exists(caseDir / "1.5" / "fluid.vtp"));
    EXPECT_TRUE(fs::exists(caseDir / "hydrostaticTank2D.pvd"));
}

} // namespace
