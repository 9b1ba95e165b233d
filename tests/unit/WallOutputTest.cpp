// What a wall system's .vtp holds: a pressure and a density only when the boundary model gives
// the walls their own (WallSystem::pressureMirrored false); with a mirroring model (akinci) the
// arrays are left out, even when writeFields names them, instead of a false 0 for ParaView. Every
// wall is written at every written time, so that its own pressure follows the flow in ParaView
// (issue 34, item 2: every time pointed at 0/tank.vtp, the t = 0 pressure).
#include "Case.hpp"
#include "Log.hpp"
#include "Simulation.hpp"
#include "TestSupport.hpp"

#include <gtest/gtest.h>
#include <cmath>
#include <fstream>

#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

using namespace spindrift;
namespace fs = std::filesystem;

namespace {

void editDictionary(const fs::path& file, const std::vector<std::pair<std::string, std::string>>& entries) {
    Dictionary d = Dictionary::fromFile(file);
    for (const auto& [key, value] : entries) d.set(key, value);
    std::ofstream(file) << d.toString();
}

// A coarse dam break (walls: the fixed container 'tank') run for two written times after 0.
fs::path makeCase(const fs::path& dir, const std::string& boundary, const std::string& libs = "()") {
    copyCaseInput(fs::path(SPINDRIFT_SOURCE_DIR) / "tutorials/damBreak2D", dir);
    editDictionary(dir / "constant/fluidProperties", {{"particleSpacing", "0.0047625"}});
    editDictionary(dir / "system/controlDict", {{"endTime", "0.002"}, {"writeInterval", "0.001"},
                                                 {"writeFields", "(velocity pressure density)"}, {"libs", libs}});
    editDictionary(dir / "system/sphSchemes", {{"boundary", boundary}});
    log::setQuiet(true);
    Simulation(dir).run();
    return dir;
}

// The point-data arrays of a .vtp file, read with VTK itself (readVtp would give every set the
// fields a ParticleSet always has).
struct VtpArrays {
    vtkNew<vtkXMLPolyDataReader> reader;
    explicit VtpArrays(const fs::path& file) {
        reader->SetFileName(file.string().c_str());
        reader->Update();
    }
    vtkDataArray* get(const char* name) { return reader->GetOutput()->GetPointData()->GetArray(name); }
    vtkIdType points() { return reader->GetOutput()->GetNumberOfPoints(); }
};

TEST(WallOutput, MirroredPressureIsNotWrittenForTheWalls) {
    test::TempDir tmp;
    const fs::path dir = makeCase(tmp.path() / "akinci", "{ type akinci; }");
    VtpArrays wall(dir / "0/tank.vtp");
    ASSERT_GT(wall.points(), 0);
    EXPECT_EQ(wall.get("pressure"), nullptr) << "akinci mirrors the fluid's pressure: the walls have none of their own";
    EXPECT_EQ(wall.get("density"), nullptr);
    EXPECT_NE(wall.get("velocity"), nullptr);
    EXPECT_NE(wall.get("id"), nullptr);
    for (const char* time : {"0", "0.002"}) {
        VtpArrays fluid(dir / time / "fluid.vtp");
        EXPECT_NE(fluid.get("pressure"), nullptr) << time;
        EXPECT_NE(fluid.get("density"), nullptr) << time;
    }
    EXPECT_TRUE(fs::exists(dir / "0.002/tank.vtp")) << "every wall at every written time";
}

// adami walls (the tutorials' default) have a pressure of their own, extrapolated from the fluid:
// each written time holds the wall's pressure of that time, and the .pvd points each time's wall
// block at that time's file.
TEST(WallOutput, AWallsOwnPressureIsWrittenAtEveryTime) {
    test::TempDir tmp;
    const fs::path dir = makeCase(tmp.path() / "adami", "{ type adami; }");
    VtpArrays first(dir / "0/tank.vtp"), last(dir / "0.002/tank.vtp");
    ASSERT_GT(first.points(), 0);
    ASSERT_EQ(first.points(), last.points());
    vtkDataArray* p0 = first.get("pressure");
    vtkDataArray* p1 = last.get("pressure");
    ASSERT_NE(p0, nullptr);
    ASSERT_NE(p1, nullptr);
    EXPECT_EQ(first.get("acceleration"), nullptr) << "no restart data for walls (sampled anew on a restart)";
    double largest = 0, changed = 0;
    for (vtkIdType i = 0; i < first.points(); ++i) {
        largest = std::max(largest, p1->GetComponent(i, 0));
        changed = std::max(changed, std::abs(p1->GetComponent(i, 0) - p0->GetComponent(i, 0)));
    }
    EXPECT_GT(largest, 100) << "the column's weight on the floor [Pa]";
    EXPECT_GT(changed, 1) << "the wall pressure of 0.002 is that time's, not t = 0's [Pa]";
    const std::string pvd = test::readFile(dir / "adami.pvd");
    for (const char* time : {"0", "0.001", "0.002"})
        EXPECT_NE(pvd.find(std::string("timestep=\"") + time + "\" group=\"\" part=\"1\" file=\"" + time + "/tank.vtp\""),
                  std::string::npos)
            << time << ": " << pvd;
}

TEST(WallOutput, OwnPressureIsWrittenForTheWalls) {
    test::TempDir tmp;
    const fs::path dir = makeCase(tmp.path() / "own", "{ type ownPressure; wallPressure 1234; }",
                                  "(\"" SPINDRIFT_TEST_PLUGIN_DIR "/libspindriftTestOwnPressureBoundary.so\")");
    VtpArrays wall(dir / "0/tank.vtp");
    ASSERT_GT(wall.points(), 0);
    vtkDataArray* pressure = wall.get("pressure");
    vtkDataArray* density = wall.get("density");
    ASSERT_NE(pressure, nullptr);
    ASSERT_NE(density, nullptr);
    for (vtkIdType i = 0; i < wall.points(); ++i) {
        ASSERT_EQ(pressure->GetComponent(i, 0), 1234) << i;
        ASSERT_EQ(density->GetComponent(i, 0), 1000) << i;
    }
}

} // namespace
