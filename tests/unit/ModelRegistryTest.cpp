// ModelRegistry: plugins by name, only the named library opened, helpful errors.
#include "TestSupport.hpp"

#include <gtest/gtest.h>
#include <cstdlib>
#include <fstream>

using namespace spindrift;

namespace {

bool loaded(const std::string& fileName) {
    for (const auto& l : ModelRegistry::instance().loadedLibraries())
        if (l.find(fileName) != std::string::npos) return true;
    return false;
}

TEST(ModelRegistry, ListsEveryFoundationPluginWithoutOpeningAny) {
    auto& r = ModelRegistry::instance();
    auto has = [&](const std::string& kind, const std::string& name) {
        const auto v = r.available(kind);
        return std::find(v.begin(), v.end(), name) != v.end();
    };
    EXPECT_TRUE(has("kernel", "cubicSpline"));
    EXPECT_TRUE(has("kernel", "wendlandC2"));
    EXPECT_TRUE(has("pressure", "wcsph"));
    EXPECT_TRUE(has("viscosity", "artificial"));
    EXPECT_TRUE(has("viscosity", "laminar"));
    EXPECT_TRUE(has("integrator", "symplecticEuler"));
    EXPECT_TRUE(has("integrator", "leapfrog"));
    EXPECT_TRUE(has("boundary", "akinci"));
    EXPECT_TRUE(r.loadedLibraries().empty()) << "listing must not open libraries";
}

TEST(ModelRegistry, OpensOnlyTheLibraryACaseNames) {
    auto k = test::createModel<Kernel>("type wendlandC2;", test::physicsFor(2));
    ASSERT_NE(k, nullptr);
    EXPECT_GT(k->W(0), 0.0);
    EXPECT_TRUE(loaded("libspindrift_kernel_wendlandC2.so"));
    EXPECT_FALSE(loaded("libspindrift_kernel_cubicSpline.so"));
    EXPECT_EQ(ModelRegistry::instance().loadedLibraries().size(), 1u);
    // a second model of the same type reuses the open library
    auto k2 = test::createModel<Kernel>("type wendlandC2;", test::physicsFor(3));
    EXPECT_EQ(ModelRegistry::instance().loadedLibraries().size(), 1u);
}

TEST(ModelRegistry, UnknownTypeListsTheValidOnes) {
    try {
        test::createModel<PressureModel>("type wcsp;", test::physicsFor(2));
        FAIL() << "expected an error";
    } catch (const InputError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("Unknown pressure type 'wcsp'. Valid pressure types are: ("), std::string::npos) << m;
        EXPECT_NE(m.find("wcsph"), std::string::npos) << m;
        EXPECT_NE(m.find("did you mean 'wcsph'"), std::string::npos) << m;
        EXPECT_NE(m.find("test:1:"), std::string::npos) << "names file and line: " << m;
    }
    EXPECT_TRUE(ModelRegistry::instance().loadedLibraries().empty());
}

TEST(ModelRegistry, UnknownKeywordInModelDictionaryIsAnError) {
    try {
        test::createModel<PressureModel>("type wcsph;\ngama 7;", test::physicsFor(2));
        FAIL() << "expected an error";
    } catch (const InputError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("gama"), std::string::npos) << m;
        EXPECT_NE(m.find("gamma"), std::string::npos) << "suggests the right keyword: " << m;
        EXPECT_NE(m.find("test:2:"), std::string::npos) << m;
    }
}

TEST(ModelRegistry, MissingTypeIsAnError) {
    EXPECT_THROW(test::createModel<Integrator>("order 2;", test::physicsFor(2)), InputError);
}

TEST(ModelRegistry, UserLibraryThatIsNotAPluginIsRefused) {
    test::TempDir dir;
    const auto where = SourceLocation{"controlDict", 3, 1};
    try {
        ModelRegistry::instance().loadUserLibrary("libm.so.6", "/lib/x86_64-linux-gnu", where);
        FAIL() << "expected an error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("not a Spindrift plugin"), std::string::npos) << e.what();
    }
    EXPECT_THROW(ModelRegistry::instance().loadUserLibrary("libdoesNotExist.so", dir.path(), where), InputError);
}

TEST(ModelRegistry, UserLibraryRegistersItsModel) {
    // Load a plugin file explicitly, as `libs ("...")` in controlDict does.
    std::string file;
    for (const auto& dir : ModelRegistry::instance().searchPath())
        if (std::filesystem::exists(dir / "libspindrift_integrator_leapfrog.so")) {
            file = (dir / "libspindrift_integrator_leapfrog.so").string();
            break;
        }
    ASSERT_FALSE(file.empty());
    ModelRegistry::instance().loadUserLibrary(file, ".", {"controlDict", 1, 1});
    EXPECT_TRUE(loaded("libspindrift_integrator_leapfrog.so"));
    auto integrator = test::createModel<Integrator>("type leapfrog;", test::physicsFor(2));
    EXPECT_NE(integrator, nullptr);
    EXPECT_EQ(ModelRegistry::instance().loadedLibraries().size(), 1u);
}

// The path of an in-tree plugin library on the search path.
std::filesystem::path pluginFile(const std::string& fileName) {
    for (const auto& dir : ModelRegistry::instance().searchPath())
        if (std::filesystem::exists(dir / fileName)) return dir / fileName;
    return {};
}

TEST(ModelRegistry, LibraryCutShortIsRefusedBeforeDlopen) {
    // issue 33.2: a copy of a plugin cut short made dlopen die of SIGBUS (exit 135). Every cut,
    // from nothing to one byte short, is refused with what is wrong, before dlopen is called.
    const auto whole = pluginFile("libspindrift_kernel_wendlandC2.so");
    ASSERT_FALSE(whole.empty());
    EXPECT_EQ(unloadableLibrary(whole), "") << "the whole library is fine";
    const std::string bytes = test::readFile(whole);
    test::TempDir dir;
    const auto size = bytes.size();
    for (std::size_t cut : {std::size_t(0), std::size_t(3), std::size_t(16), std::size_t(63), std::size_t(64),
                            std::size_t(200), size / 4, size / 2, size - 4096, size - 1}) {
        const std::filesystem::path file = dir.path() / ("libcut" + std::to_string(cut) + ".so");
        std::ofstream(file, std::ios::binary).write(bytes.data(), std::streamsize(cut));
        const std::string why = unloadableLibrary(file);
        EXPECT_FALSE(why.empty()) << "cut at " << cut;
        if (cut >= 64) {
            EXPECT_NE(why.find("it is cut short"), std::string::npos) << why;
            EXPECT_NE(why.find("the file has " + std::to_string(cut) + " bytes"), std::string::npos) << why;
        }
        // through the registry, as controlDict's libs: an InputError at the entry, no signal
        try {
            ModelRegistry::instance().loadUserLibrary(file.string(), dir.path(), {"controlDict", 9, 1});
            ADD_FAILURE() << "loaded a library cut at " << cut;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("controlDict:9:1: error: cannot load plugin library '" + file.string() + "': "),
                      std::string::npos)
                << e.what();
        }
    }
    EXPECT_TRUE(ModelRegistry::instance().loadedLibraries().empty());
    // not an ELF file at all, and an object file
    const auto text = dir.writeFile("libtext.so", "not a library\n");
    EXPECT_EQ(unloadableLibrary(text), "it is not a shared library (no ELF header; 14 bytes)");
    std::string object = bytes;
    object[16] = 1; // e_type ET_REL (little-endian)
    object[17] = 0;
    std::ofstream(dir.path() / "libobject.so", std::ios::binary) << object;
    EXPECT_EQ(unloadableLibrary(dir.path() / "libobject.so"), "it is an object file (.o), not a shared library");
    std::string otherMachine = bytes;
    otherMachine[18] = bytes[18] == 62 ? char(183) : char(62); // e_machine: AArch64 on x86-64, else x86-64
    otherMachine[19] = 0;
    std::ofstream(dir.path() / "libother.so", std::ios::binary) << otherMachine;
    EXPECT_NE(unloadableLibrary(dir.path() / "libother.so").find("it is built for "), std::string::npos);
}

TEST(ModelRegistry, BareLibraryNamesAreFoundInTheCaseDirectoryThePluginPathAndLdLibraryPath) {
    // issue 34.9: `libs ("libmyIntegrator.so")` and OpenFOAM's short `libs (myIntegrator)`
    const auto leapfrog = pluginFile("libspindrift_integrator_leapfrog.so");
    ASSERT_FALSE(leapfrog.empty());
    test::TempDir dir;
    const auto caseDir = dir.path() / "case";
    std::filesystem::create_directories(caseDir);
    std::filesystem::copy_file(leapfrog, caseDir / "libmyIntegrator.so");
    auto& registry = ModelRegistry::instance();
    registry.loadUserLibrary("myIntegrator", caseDir, {"controlDict", 3, 1});
    ASSERT_EQ(registry.loadedLibraries().size(), 1u);
    EXPECT_EQ(registry.loadedLibraries()[0], std::filesystem::canonical(caseDir / "libmyIntegrator.so").string());
    registry.loadUserLibrary("libmyIntegrator.so", caseDir, {"controlDict", 3, 1}); // the same file: once
    EXPECT_EQ(registry.loadedLibraries().size(), 1u);
    // a directory of LD_LIBRARY_PATH (read when asked)
    const auto libDir = dir.path() / "lib";
    std::filesystem::create_directories(libDir);
    std::filesystem::copy_file(pluginFile("libspindrift_integrator_velocityVerlet.so"), libDir / "libmyVerlet.so");
    const char* previous = std::getenv("LD_LIBRARY_PATH");
    const std::string saved = previous ? previous : "";
    ::setenv("LD_LIBRARY_PATH", ("/nonexistent:" + libDir.string()).c_str(), 1);
    registry.loadUserLibrary("libmyVerlet", dir.path() / "elsewhere", {"controlDict", 3, 1});
    EXPECT_EQ(registry.loadedLibraries().size(), 2u);
    // not found: every directory looked in, in order
    try {
        registry.loadUserLibrary("libnotThere.so", caseDir, {"controlDict", 4, 1});
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("controlDict:4:1: error: cannot find library 'libnotThere.so' (looked in " + caseDir.string() + ", "),
                  std::string::npos)
            << m;
        for (const auto& d : registry.searchPath()) EXPECT_NE(m.find(d.string()), std::string::npos) << d << " in " << m;
        EXPECT_NE(m.find("/nonexistent, " + libDir.string() + ": the case directory, SPINDRIFT_PLUGIN_PATH"), std::string::npos) << m;
    }
    if (previous) ::setenv("LD_LIBRARY_PATH", saved.c_str(), 1);
    else ::unsetenv("LD_LIBRARY_PATH");
}

} // namespace

namespace {

std::string precisionOf(bool single) {
    return single ? "single precision (Scalar = float)" : "double precision (Scalar = double)";
}

// The message a plugin built for the other precision gets, at 'file' (path as loaded).
std::string otherPrecisionMessage(const std::string& file) {
    const std::string interface = "interface " + std::to_string(pluginInterfaceVersion);
    return "plugin '" + file + "' was built for " + precisionOf(!test::singlePrecision) + ", " + interface +
           "; this spindrift is " + precisionOf(test::singlePrecision) + ", " + interface +
           ": rebuild the plugin against this installation";
}

std::string messageOfLoading(const std::filesystem::path& file) {
    try {
        ModelRegistry::instance().loadUserLibrary(file.string(), ".", {"controlDict", 7, 1});
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(ModelRegistry, PluginBuiltForTheOtherPrecisionIsRefusedWithBothPrecisions) {
    const auto file = std::filesystem::path(SPINDRIFT_TEST_PLUGIN_DIR) / "libspindriftTestOtherPrecision.so";
    const std::string m = messageOfLoading(file);
    EXPECT_NE(m.find(otherPrecisionMessage(file.string())), std::string::npos) << m;
    EXPECT_NE(m.find("controlDict:7:1"), std::string::npos) << m;
    EXPECT_TRUE(ModelRegistry::instance().loadedLibraries().empty());
}

TEST(ModelRegistry, PluginOfTheOtherPrecisionThatCannotBeBoundIsRefusedWithItsPrecision) {
    // Its constructor calls Dictionary::getOrDefault<Vec3> of the other precision, which this
    // core lacks: loading with every symbol bound fails; the message still says why.
    const auto file = std::filesystem::path(SPINDRIFT_TEST_PLUGIN_DIR) / "libspindriftTestOtherPrecisionCallsCore.so";
    const std::string m = messageOfLoading(file);
    EXPECT_NE(m.find(otherPrecisionMessage(file.string())), std::string::npos) << m;
    EXPECT_TRUE(ModelRegistry::instance().loadedLibraries().empty());
}

TEST(ModelRegistry, PluginOfAnotherInterfaceIsRefused) {
    const auto file = std::filesystem::path(SPINDRIFT_TEST_PLUGIN_DIR) / "libspindriftTestWrongAbi.so";
    const std::string m = messageOfLoading(file);
    EXPECT_NE(m.find("plugin '" + file.string() + "' was built for " + precisionOf(test::singlePrecision) +
                     ", interface 999; this spindrift is " + precisionOf(test::singlePrecision) + ", interface " +
                     std::to_string(pluginInterfaceVersion) + ": rebuild the plugin against this installation"),
              std::string::npos)
        << m;
}

TEST(ModelRegistry, PluginFileOfAnotherKindIsRefusedBeforeItsFactoryIsCalled) {
    // libspindrift_pressure_mislabelled.so holds a kernel: calling its factory as a
    // PressureModel's would be undefined behaviour.
    ModelRegistry::instance().prependSearchDirectory(SPINDRIFT_TEST_PLUGIN_DIR);
    try {
        test::createModel<PressureModel>("type mislabelled;", test::physicsFor(2));
        FAIL() << "expected an error";
    } catch (const InputError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("plugin '" + (std::filesystem::path(SPINDRIFT_TEST_PLUGIN_DIR) /
                                       "libspindrift_pressure_mislabelled.so").string() +
                         "' is the kernel 'mislabelled', not the pressure 'mislabelled' its file name says"),
                  std::string::npos)
            << m;
        EXPECT_NE(m.find("test:1:"), std::string::npos) << "names the type entry: " << m;
    }
    EXPECT_TRUE(ModelRegistry::instance().loadedLibraries().empty()) << "refused, not registered";
}

TEST(ModelRegistry, PluginsCarryTheKindOfTheirBaseClassAndTheNameOfTheirCMakeCall) {
    // every in-tree plugin: file name, exported kind and name agree (else factoryFor refuses)
    auto k = test::createModel<Kernel>("type cubicSpline;", test::physicsFor(2));
    auto p = test::createModel<PressureModel>("type wcsph; soundSpeed 20;", test::physicsFor(2));
    auto f = test::createModel<ExtraForce>("type vorticityConfinement; epsilon 0.1;", test::physicsFor(2));
    EXPECT_NE(k, nullptr);
    EXPECT_NE(p, nullptr);
    EXPECT_NE(f, nullptr);
    EXPECT_EQ(ModelRegistry::instance().loadedLibraries().size(), 3u);
}

} // namespace

// The kinds are listed by ModelRegistry::kinds(); CMake's spindrift_add_plugin and the bash
// completion cannot ask it, so they carry a copy each: it must be the same list.
TEST(ModelRegistry, KindListsAgreeEverywhere) {
    std::string kinds;
    for (const auto& k : ModelRegistry::kinds()) kinds += (kinds.empty() ? "" : " ") + k;
    const std::string cmake = test::readFile(std::filesystem::path(SPINDRIFT_SOURCE_DIR) / "cmake/SpindriftPlugin.cmake");
    EXPECT_NE(cmake.find("set(kinds " + kinds + ")"), std::string::npos) << "cmake/SpindriftPlugin.cmake: " << kinds;
    const std::string completion = test::readFile(std::filesystem::path(SPINDRIFT_SOURCE_DIR) / "etc/bash-completion/spindrift");
    EXPECT_NE(completion.find("kinds=\"" + kinds + "\""), std::string::npos) << "etc/bash-completion/spindrift: " << kinds;
}
