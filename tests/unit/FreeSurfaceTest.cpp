// freeSurface (plugins/functionObjects/freeSurface): the mesh of a block of fluid at rest is flat
// within half a particle spacing of the fluid's top and closed (3D: every edge of two triangles;
// 2D: every point of two segments); a ball of particles gives a closed mesh enclosing the
// particles' volume; bad options are errors naming their keyword; a run writes the block into
// every time directory and lists it in the .pvd (the core's block hook, CaseWriter::Block).
#include "Case.hpp"
#include "CaseWriter.hpp"
#include "Log.hpp"
#include "Simulation.hpp"
#include "TestSupport.hpp"

#include <gtest/gtest.h>

#include <vtkCellArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include <array>
#include <cmath>
#include <fstream>
#include <map>

using namespace spindrift;
namespace fs = std::filesystem;

namespace {

constexpr double dx = 0.01;

struct Mesh {
    std::vector<std::array<double, 3>> points;
    std::vector<std::vector<vtkIdType>> cells; // triangles (3D) or line segments (2D)
};

Mesh readMesh(const fs::path& file) {
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName(file.string().c_str());
    reader->Update();
    vtkPolyData* poly = reader->GetOutput();
    Mesh m;
    for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i) {
        std::array<double, 3> p;
        poly->GetPoint(i, p.data());
        m.points.push_back(p);
    }
    for (vtkCellArray* cells : {poly->GetPolys(), poly->GetLines()}) {
        vtkNew<vtkIdList> ids;
        for (cells->InitTraversal(); cells->GetNextCell(ids);) {
            std::vector<vtkIdType> cell;
            for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k) cell.push_back(ids->GetId(k));
            m.cells.push_back(cell);
        }
    }
    return m;
}

// Edges (3D) or points (2D) not shared by exactly two cells: 0 for a closed mesh.
long openOrNonManifold(const Mesh& m) {
    std::map<std::pair<vtkIdType, vtkIdType>, int> uses;
    for (const auto& c : m.cells) {
        if (c.size() == 2) { // a segment: its points
            ++uses[{c[0], -1}];
            ++uses[{c[1], -1}];
            continue;
        }
        for (std::size_t k = 0; k < c.size(); ++k) {
            const vtkIdType a = c[k], b = c[(k + 1) % c.size()];
            ++uses[{std::min(a, b), std::max(a, b)}];
        }
    }
    long bad = 0;
    for (const auto& [edge, n] : uses) bad += n != 2;
    return bad;
}

// Volume a closed triangle mesh encloses (divergence theorem, Σ p0·(p1×p2)/6).
double enclosedVolume(const Mesh& m) {
    double v = 0;
    for (const auto& c : m.cells) {
        const auto &a = m.points[c[0]], &b = m.points[c[1]], &d = m.points[c[2]];
        v += a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) + a[2] * (b[0] * d[1] - b[1] * d[0]);
    }
    return std::abs(v) / 6;
}

// A scene of fluid particles at 'positions' (spacing dx, density ρ0, volume dx^dim each).
struct SurfaceScene {
    Scene s;
    test::TempDir dir{"spindrift-freesurface-test"};
    std::vector<std::unique_ptr<Dictionary>> dicts;

    SurfaceScene(int dim, const std::vector<Vec3>& positions) {
        s.physics = test::physicsFor(dim, Scalar(dx));
        auto& set = test::addFluid(s, positions.size()).particles;
        set.setParticleMass(Scalar(s.physics.rho0 * std::pow(dx, dim)));
        for (std::size_t i = 0; i < positions.size(); ++i) set.position()[i] = positions[i];
    }
    std::unique_ptr<FunctionObject> create(const std::string& text, const std::string& name = "surface") {
        dicts.push_back(std::make_unique<Dictionary>(Dictionary::fromString(text, "controlDict.functions." + name)));
        return ModelRegistry::instance().create<FunctionObject>(*dicts.back(), s.physics, s.constants, nullptr,
                                                                dir.path(), name);
    }
    Mesh mesh(const std::string& text = "type freeSurface;") {
        auto surface = create(text);
        EXPECT_EQ(surface->blockName(), "surface");
        const fs::path file = dir.path() / "surface.vtp";
        surface->writeBlock(s, file);
        return readMesh(file);
    }
};

// Cell centres of a lattice of spacing dx filling [0, n0 dx) × [0, n1 dx) (× [0, n2 dx) in 3D).
std::vector<Vec3> block(int n0, int n1, int n2) {
    std::vector<Vec3> x;
    for (int k = 0; k < std::max(n2, 1); ++k)
        for (int j = 0; j < n1; ++j)
            for (int i = 0; i < n0; ++i) x.emplace_back((i + 0.5) * dx, (j + 0.5) * dx, n2 ? (k + 0.5) * dx : 0.0);
    return x;
}

// Heights (coordinate 'up') of the mesh points over the top face's middle (the points above
// half the depth, two kernel radii from every side wall): their lowest and highest.
std::pair<double, double> topFace(const Mesh& m, int up, double depth, double width) {
    double lo = 1e30, hi = -1e30;
    const double margin = 4 * dx;
    for (const auto& p : m.points) {
        if (p[up] < 0.5 * depth) continue;
        bool inside = true;
        for (int k = 0; k < up; ++k) inside = inside && p[k] > margin && p[k] < width - margin;
        if (!inside) continue;
        lo = std::min(lo, p[up]);
        hi = std::max(hi, p[up]);
    }
    return {lo, hi};
}

TEST(FreeSurface, TankAtRest3DIsFlatAndClosed) {
    const int n = 24, depth = 12; // 24 × 24 × 12 particles: the surface at z = 0.12
    SurfaceScene sc(3, block(n, n, depth));
    for (const char* options : {"type freeSurface;", "type freeSurface; cellSize 0.5;"}) {
        const Mesh m = sc.mesh(options);
        ASSERT_GT(m.cells.size(), 100u) << options;
        EXPECT_EQ(openOrNonManifold(m), 0) << options;
        for (const auto& c : m.cells) ASSERT_EQ(c.size(), 3u);
        const auto [lo, hi] = topFace(m, 2, depth * dx, n * dx);
        std::cout << options << " " << m.cells.size() << " triangles; top face between " << (lo - depth * dx) / dx
                  << " and " << (hi - depth * dx) / dx << " dx of the fluid's top; volume "
                  << 100 * (enclosedVolume(m) / (n * n * depth * dx * dx * dx) - 1) << " % off\n";
        EXPECT_LT(std::abs(lo - depth * dx), 0.5 * dx) << options;
        EXPECT_LT(std::abs(hi - depth * dx), 0.5 * dx) << options;
        EXPECT_NEAR(enclosedVolume(m), n * n * depth * dx * dx * dx, 0.02 * n * n * depth * dx * dx * dx) << options;
    }
}

TEST(FreeSurface, TankAtRest2DIsAFlatClosedContour) {
    const int n = 30, depth = 20;
    SurfaceScene sc(2, block(n, depth, 0));
    const Mesh m = sc.mesh();
    ASSERT_GT(m.cells.size(), 40u);
    for (const auto& c : m.cells) ASSERT_EQ(c.size(), 2u); // line segments in the plane
    for (const auto& p : m.points) ASSERT_EQ(p[2], 0.0);
    EXPECT_EQ(openOrNonManifold(m), 0);
    const auto [lo, hi] = topFace(m, 1, depth * dx, n * dx);
    EXPECT_LT(std::abs(lo - depth * dx), 0.5 * dx);
    EXPECT_LT(std::abs(hi - depth * dx), 0.5 * dx);
}

TEST(FreeSurface, BallOfParticlesEnclosesTheirVolume) {
    // the lattice points within 8 dx of the centre: volume N dx³
    std::vector<Vec3> ball;
    for (int i = -9; i <= 9; ++i)
        for (int j = -9; j <= 9; ++j)
            for (int k = -9; k <= 9; ++k)
                if (i * i + j * j + k * k <= 64) ball.emplace_back(i * dx, j * dx, k * dx);
    SurfaceScene sc(3, ball);
    const double particles = ball.size() * dx * dx * dx;
    for (const char* options : {"type freeSurface;", "type freeSurface; cellSize 0.5;"}) {
        const Mesh m = sc.mesh(options);
        EXPECT_EQ(openOrNonManifold(m), 0) << options;
        const double volume = enclosedVolume(m);
        std::cout << options << " ball of " << ball.size() << " particles: " << m.cells.size() << " triangles, volume "
                  << 100 * (volume / particles - 1) << " % off\n";
        EXPECT_NEAR(volume, particles, 0.03 * particles) << options;
        // round: every point within a spacing of the sphere of the particles' volume
        const double radius = std::cbrt(3 * particles / (4 * M_PI));
        for (const auto& p : m.points) ASSERT_NEAR(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), radius, dx);
    }
}

TEST(FreeSurface, NoFluidGivesAnEmptyBlock) {
    SurfaceScene sc(3, {});
    EXPECT_TRUE(sc.mesh().cells.empty());
}

TEST(FreeSurface, BadOptionsAreErrorsNamingTheKeyword) {
    SurfaceScene sc(3, block(4, 4, 4));
    for (const auto& [text, keyword] : std::vector<std::pair<std::string, std::string>>{
             {"type freeSurface;\ncellSize -1;", "cellSize"},
             {"type freeSurface;\nisoValue 1.5;", "isoValue"},
             {"type freeSurface;\nkernelRadius 0.5;", "kernelRadius"},
             {"type freeSurface;\ncellSize fine;", "cellSize"}}) {
        try {
            sc.create(text);
            FAIL() << text;
        } catch (const InputError& e) {
            EXPECT_EQ(e.keyword(), keyword) << e.what();
            EXPECT_NE(std::string(e.what()).find("controlDict.functions.surface:2"), std::string::npos) << e.what();
        }
    }
}

// The hydrostaticTank2D tutorial (copied) with the function object: every written time holds
// surface.vtp, listed in the .pvd; the settled surface is flat within half a spacing and closed.
TEST(FreeSurface, SettledTankRunWritesAFlatClosedSurfaceAtEveryTime) {
    log::setQuiet(true);
    test::TempDir tmp;
    const fs::path caseDir = tmp.path() / "hydrostaticTank2D";
    copyCaseInput(fs::path(SPINDRIFT_SOURCE_DIR) / "tutorials" / "hydrostaticTank2D", caseDir);
    std::ofstream(caseDir / "system" / "controlDict", std::ios::app)
        << "functions { surface { type freeSurface; cellSize 0.5; } }\n";
    Simulation sim(caseDir);
    sim.run();
    const std::string pvd = test::readFile(caseDir / "hydrostaticTank2D.pvd");
    for (const char* time : {"0", "0.1", "1.5"}) {
        EXPECT_TRUE(fs::exists(caseDir / time / "surface.vtp")) << time;
        EXPECT_NE(pvd.find(std::string("file=\"") + time + "/surface.vtp\" name=\"surface\""), std::string::npos) << pvd;
    }
    // the settled level: the top particles' height + dx/2
    double top = 0;
    for (const auto& x : test::fluidOf(sim.scene()).particles.position()) top = std::max(top, double(x.y()));
    top += 0.5 * dx;
    const Mesh m = readMesh(caseDir / "1.5" / "surface.vtp");
    EXPECT_EQ(openOrNonManifold(m), 0);
    const auto [lo, hi] = topFace(m, 1, 0.3, 0.2);
    std::cout << "settled hydrostaticTank2D: surface between " << (lo - top) / dx << " and " << (hi - top) / dx
              << " dx of the top particles' + dx/2\n";
    EXPECT_LT(hi - lo, 0.5 * dx);
    EXPECT_LT(std::abs(lo - top), 0.5 * dx);
    EXPECT_LT(std::abs(hi - top), 0.5 * dx);
}

// A block named as a particle system would replace its file: refused at set-up.
TEST(FreeSurface, ABlockNamedAsASystemIsAnInputError) {
    log::setQuiet(true);
    test::TempDir tmp;
    const fs::path caseDir = tmp.path() / "hydrostaticTank2D";
    copyCaseInput(fs::path(SPINDRIFT_SOURCE_DIR) / "tutorials" / "hydrostaticTank2D", caseDir);
    std::ofstream(caseDir / "system" / "controlDict", std::ios::app) << "functions { tank { type freeSurface; } }\n";
    try {
        Simulation sim(caseDir);
        FAIL() << "a block named 'tank' (the wall system) must be refused";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("tank.vtp"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("controlDict"), std::string::npos) << e.what();
    }
}

} // namespace
