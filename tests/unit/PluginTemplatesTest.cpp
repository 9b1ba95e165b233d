// etc/templates/<kind>/: every plugin template, compiled in the tree against the current
// interfaces (tests/plugins/CMakeLists.txt), loads as a plugin of its kind and makes its model;
// the kernel template is a real kernel (Wendland C2, the same values as the wendlandC2 plugin).
#include "TestSupport.hpp"

#include <gtest/gtest.h>

using namespace spindrift;

namespace {

std::string load(const std::string& kind) {
    const std::string name = kind + "Template";
    ModelRegistry::instance().loadUserLibrary(
        (std::filesystem::path(SPINDRIFT_TEMPLATE_PLUGIN_DIR) / pluginFileName(kind, name)).string(), ".",
        {"controlDict", 1, 1});
    return name;
}

TEST(PluginTemplates, EveryKindHasATemplateThatLoadsAndMakesItsModel) {
    const auto physics = test::physicsFor(2);
    EXPECT_NE(test::createModel<Kernel>("type " + load("kernel") + ";", physics), nullptr);
    EXPECT_NE(test::createModel<PressureModel>("type " + load("pressure") + "; soundSpeed 20;", physics), nullptr);
    EXPECT_NE(test::createModel<ViscosityModel>("type " + load("viscosity") + "; c 0.01;", physics), nullptr);
    EXPECT_NE(test::createModel<Integrator>("type " + load("integrator") + ";", physics), nullptr);
    EXPECT_NE(test::createModel<BoundaryModel>("type " + load("boundary") + ";", physics), nullptr);
    EXPECT_NE(test::createModel<ExtraForce>("type " + load("force") + "; acceleration (1 0 0);", physics), nullptr);
    EXPECT_NE(test::createModel<FunctionObject>("type " + load("functionObject") + ";", physics), nullptr);
    EXPECT_NE(test::createModel<DensityDiffusion>("type " + load("densityDiffusion") + ";", physics), nullptr);
    EXPECT_NE(test::createModel<ShiftingModel>("type " + load("shifting") + ";", physics), nullptr);
    EXPECT_NE(test::createModel<SurfaceTensionModel>("type " + load("surfaceTension") + "; sigma 0.07;", physics),
              nullptr);
    EXPECT_NE(test::createModel<PassiveModel>("type " + load("passive") + "; min (0 0 0); max (1 1 0); spacing 0.1;", physics),
              nullptr);
    EXPECT_EQ(ModelRegistry::instance().loadedLibraries().size(), ModelRegistry::kinds().size());
}

TEST(PluginTemplates, KernelTemplateIsWendlandC2) {
    for (int dim : {2, 3}) {
        const auto physics = test::physicsFor(dim);
        const auto copy = test::createModel<Kernel>("type " + load("kernel") + ";", physics);
        const auto real = test::createModel<Kernel>("type wendlandC2;", physics);
        const Scalar h = test::constantsFor(physics).supportRadius;
        for (Scalar r : {Scalar(0), Scalar(0.1) * h, Scalar(0.5) * h, Scalar(0.9) * h, h}) {
            EXPECT_SCALAR_EQ(copy->W(r), real->W(r)) << "dim " << dim << " r " << r;
            EXPECT_SCALAR_EQ(copy->dWdr(r), real->dWdr(r)) << "dim " << dim << " r " << r;
        }
        EXPECT_SCALAR_EQ(copy->laplacian(Scalar(0.5) * h), real->laplacian(Scalar(0.5) * h));
    }
}

} // namespace
