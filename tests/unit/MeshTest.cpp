// Meshes in constant/geometry (TriangleMesh, SurfaceSampling; issue 38 item 1): STL (ASCII and
// binary) and OBJ read alike; a closed cube gives exactly the `box` primitive's particles as a wall
// and as a fluid region; the winding number of a curved closed mesh against the sphere it
// approximates; Poisson-disk walls' least spacing and coverage; fluid in a shaken sphere stays in
// it; a hydrostatic tank on a Poisson-disk wall (akinci); bad meshes get clear errors.
#include "Case.hpp"
#include "Geometry.hpp"
#include "Log.hpp"
#include "Motion.hpp"
#include "Simulation.hpp"
#include "SurfaceSampling.hpp"
#include "TestSupport.hpp"
#include "TriangleMesh.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

using namespace spindrift;
namespace fs = std::filesystem;
using V = TriangleMesh::V;
using Tri = std::array<int, 3>;

namespace {

struct Mesh {
    std::vector<V> x;
    std::vector<Tri> t;
};

// An axis-aligned box, normals outwards (12 triangles).
Mesh boxMesh(const V& lo, const V& hi) {
    Mesh m;
    for (int k = 0; k < 8; ++k) m.x.emplace_back(k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]);
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
        m.t.push_back({q[0], q[1], q[2]});
        m.t.push_back({q[0], q[2], q[3]});
    }
    return m;
}

// The same box without its top face (y = hi): an open tank.
Mesh openTankMesh(const V& lo, const V& hi) {
    const Mesh box = boxMesh(lo, hi);
    Mesh open;
    open.x = box.x;
    for (std::size_t k = 0; k < box.t.size(); ++k)
        if (k / 2 != 3) open.t.push_back(box.t[k]);
    return open;
}

// An icosphere of radius R: 20·4^level triangles (level 3: 1280, level 4: 5120), normals outwards.
Mesh icosphere(double R, int level, const V& centre = V::Zero()) {
    const double p = (1 + std::sqrt(5.0)) / 2;
    Mesh m;
    m.x = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0}, {0, -1, p}, {0, 1, p},
           {0, -1, -p}, {0, 1, -p}, {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
    for (auto& v : m.x) v.normalize();
    m.t = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
           {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
           {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    for (int l = 0; l < level; ++l) {
        std::map<std::pair<int, int>, int> mid;
        const auto middle = [&](int a, int b) {
            const auto key = std::make_pair(std::min(a, b), std::max(a, b));
            const auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            m.x.push_back((m.x[a] + m.x[b]).normalized());
            return mid[key] = int(m.x.size()) - 1;
        };
        std::vector<Tri> next;
        for (const auto& t : m.t) {
            const int a = middle(t[0], t[1]), b = middle(t[1], t[2]), c = middle(t[2], t[0]);
            next.push_back({t[0], a, c});
            next.push_back({t[1], b, a});
            next.push_back({t[2], c, b});
            next.push_back({a, b, c});
        }
        m.t = next;
    }
    for (auto& v : m.x) v = centre + R * v;
    return m;
}

void writeAsciiStl(const fs::path& file, const Mesh& m) {
    fs::create_directories(file.parent_path());
    std::ofstream out(file);
    out.precision(17);
    out << "solid test\n";
    for (const auto& t : m.t) {
        const V n = (m.x[t[1]] - m.x[t[0]]).cross(m.x[t[2]] - m.x[t[0]]).normalized();
        out << " facet normal " << n.transpose() << "\n  outer loop\n";
        for (int k = 0; k < 3; ++k) out << "   vertex " << m.x[t[k]].transpose() << "\n";
        out << "  endloop\n endfacet\n";
    }
    out << "endsolid test\n";
}

void writeBinaryStl(const fs::path& file, const Mesh& m) {
    fs::create_directories(file.parent_path());
    std::ofstream out(file, std::ios::binary);
    char header[80] = {};
    std::strncpy(header, "binary test mesh", sizeof header);
    out.write(header, 80);
    const std::uint32_t n = std::uint32_t(m.t.size());
    out.write(reinterpret_cast<const char*>(&n), 4);
    for (const auto& t : m.t) {
        const V nn = (m.x[t[1]] - m.x[t[0]]).cross(m.x[t[2]] - m.x[t[0]]).normalized();
        float f[12];
        for (int a = 0; a < 3; ++a) f[a] = float(nn[a]);
        for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a) f[3 + 3 * k + a] = float(m.x[t[k]][a]);
        out.write(reinterpret_cast<const char*>(f), sizeof f);
        const std::uint16_t attribute = 0;
        out.write(reinterpret_cast<const char*>(&attribute), 2);
    }
}

void writeObj(const fs::path& file, const Mesh& m) {
    fs::create_directories(file.parent_path());
    std::ofstream out(file);
    out.precision(17);
    for (const auto& v : m.x) out << "v " << v.transpose() << "\n";
    for (const auto& t : m.t) out << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
}

SampledGeometry sample(const fs::path& caseDir, const std::string& geometryText, double dx, int dim,
                       const Vec3& gravity = Vec3::Zero()) {
    fs::create_directories(caseDir / "constant");
    const Dictionary d = Dictionary::fromString(geometryText, (caseDir / "constant" / "geometry").string());
    return sampleGeometry(d, Scalar(dx), dim, gravity);
}

std::vector<Vec3> sorted(std::vector<Vec3> p) {
    std::sort(p.begin(), p.end(), [](const Vec3& a, const Vec3& b) {
        return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
    });
    return p;
}

// Same count, and each position within 'tol' of the other set's (both sorted).
void expectSameSets(const std::vector<Vec3>& a, const std::vector<Vec3>& b, double tol) {
    ASSERT_EQ(a.size(), b.size());
    const auto sa = sorted(a), sb = sorted(b);
    double worst = 0;
    for (std::size_t i = 0; i < sa.size(); ++i) worst = std::max(worst, double((sa[i] - sb[i]).norm()));
    EXPECT_LE(worst, tol);
}

const double dx = 0.02;
const double sameTol = test::tol(1e-12, 1e-5) * dx;

TEST(Mesh, CubeInStlAsciiStlBinaryAndObjReadAlike) {
    test::TempDir tmp;
    const Mesh cube = boxMesh(V(0.04, 0.1, -0.06), V(0.24, 0.3, 0.14));
    writeAsciiStl(tmp.path() / "a.stl", cube);
    writeBinaryStl(tmp.path() / "b.stl", cube);
    writeObj(tmp.path() / "c.obj", cube);
    for (const char* f : {"a.stl", "b.stl", "c.obj"}) {
        TriangleMesh m = TriangleMesh::read(tmp.path() / f, {});
        EXPECT_EQ(m.triangles().size(), 12u) << f;
        EXPECT_EQ(m.vertices().size(), 8u) << f; // welded
        EXPECT_EQ(m.openEdges(), 0u) << f;
        EXPECT_EQ(m.inconsistentEdges(), 0u) << f;
        EXPECT_NEAR(m.signedVolume(), 0.2 * 0.2 * 0.2, 1e-6) << f; // (the binary file holds floats)
        EXPECT_NEAR(m.area(), 6 * 0.04, 1e-6) << f;
    }
    // scale, rotate, translate: a quarter turn about z, then a shift (Assimp keeps coordinates in
    // single precision: 0.04 is read as 0.04f)
    TriangleMesh m = TriangleMesh::read(tmp.path() / "a.stl", {});
    m.transform(2, V(0, 0, 90), V(1, 0, 0));
    EXPECT_NEAR(m.signedVolume(), 8 * 0.008, 1e-7);
    EXPECT_NEAR(m.boundsMin()[0], 1 - 0.6, 1e-7); // y ∈ [0.2, 0.6] → x = −y + 1
    EXPECT_NEAR(m.boundsMax()[1], 0.48, 1e-7);    // x ∈ [0.08, 0.48] → y
    EXPECT_NEAR(m.boundsMin()[2], -0.12, 1e-7);
}

// Issue 38's target: a closed cube STL gives the `box` primitive's particles, as a wall and as a
// fluid region: same count, positions within 1e-12 Δx.
TEST(Mesh, ClosedCubeIsTheBoxPrimitive) {
    log::setQuiet(true);
    test::TempDir tmp;
    const V lo(0.04, 0.1, -0.06), hi(0.24, 0.3, 0.14);
    writeAsciiStl(tmp.path() / "constant/triSurface/cube.stl", boxMesh(lo, hi));
    const std::string fluidBox = "water { type box; min (0.4 0.1 -0.06); max (0.5 0.2 0.04); }";
    const auto boxWall = sample(tmp.path(), "fluid { " + fluidBox + " } walls { cube { type box; min (0.04 0.1 -0.06); "
                                             "max (0.24 0.3 0.14); layers 3; } }", dx, 3);
    const auto meshWall = sample(tmp.path(), "fluid { " + fluidBox + " } walls { cube { type mesh; file \"cube.stl\"; "
                                              "layers 3; } }", dx, 3);
    ASSERT_EQ(boxWall.walls.size(), 1u);
    ASSERT_EQ(meshWall.walls.size(), 1u);
    EXPECT_EQ(meshWall.walls[0].positions.size(), 10u * 10 * 10 - 4u * 4 * 4);
    expectSameSets(meshWall.walls[0].positions, boxWall.walls[0].positions, sameTol);
    expectSameSets(meshWall.fluidPositions, boxWall.fluidPositions, sameTol);

    const auto boxFluid = sample(tmp.path(), "fluid { water { type box; min (0.04 0.1 -0.06); max (0.24 0.3 0.14); } }", dx, 3);
    const auto meshFluid = sample(tmp.path(), "fluid { water { type mesh; file \"cube.stl\"; } }", dx, 3);
    EXPECT_EQ(meshFluid.fluidPositions.size(), 1000u);
    expectSameSets(meshFluid.fluidPositions, boxFluid.fluidPositions, sameTol);

    // a box of fluid around the cube as a solid wall: the same particles removed as the box's
    const std::string around = "fluid { water { type box; min (0 0 -0.1); max (0.3 0.4 0.2); } } walls { cube { type ";
    const auto boxClip = sample(tmp.path(), around + "box; min (0.04 0.1 -0.06); max (0.24 0.3 0.14); } }", dx, 3);
    const auto meshClip = sample(tmp.path(), around + "mesh; file \"cube.stl\"; } }", dx, 3);
    EXPECT_EQ(boxClip.fluidPositions.size(), 15u * 20 * 15 - 1000u);
    expectSameSets(meshClip.fluidPositions, boxClip.fluidPositions, sameTol);

    // 2D: the section z = 0 of the cube (it spans z from −0.06 to 0.14)
    const auto boxWall2 = sample(tmp.path(), "fluid { water { type box; min (0.4 0.1 0); max (0.5 0.2 0); } } walls { cube "
                                             "{ type box; min (0.04 0.1 0); max (0.24 0.3 0); layers 3; } }", dx, 2);
    const auto meshWall2 = sample(tmp.path(), "fluid { water { type box; min (0.4 0.1 0); max (0.5 0.2 0); } } walls { "
                                              "cube { type mesh; file \"cube.stl\"; layers 2; } }", dx, 2);
    // (layers 2 of the mesh: its section's lattice points nearer than 2 Δx to the sides; the
    // faces z = −0.06 and 0.14 are 3 Δx and more away)
    const auto boxWall2b = sample(tmp.path(), "fluid { water { type box; min (0.4 0.1 0); max (0.5 0.2 0); } } walls { "
                                              "cube { type box; min (0.04 0.1 0); max (0.24 0.3 0); layers 2; } }", dx, 2);
    expectSameSets(meshWall2.walls[0].positions, boxWall2b.walls[0].positions, sameTol);
    EXPECT_EQ(boxWall2.walls[0].positions.size(), 100u - 16u);
}

TEST(Mesh, WindingNumberOfACurvedMesh) {
    const Mesh s = icosphere(0.1, 4, V(0.3, 0.2, 0.1));
    ASSERT_GE(s.t.size(), 2000u);
    TriangleMesh m = TriangleMesh::fromTriangles(s.x, s.t);
    EXPECT_EQ(m.openEdges(), 0u);
    EXPECT_EQ(m.inconsistentEdges(), 0u);
    EXPECT_NEAR(m.signedVolume(), 4.0 / 3 * M_PI * 1e-3, 0.01 * 4.0 / 3 * M_PI * 1e-3);
    m.prepare();
    // the faceted sphere lies between 0.998 R and R: points off that shell are decided by |p − c|
    std::mt19937 random(7);
    std::uniform_real_distribution<double> u(-0.15, 0.15);
    int checked = 0, wrong = 0;
    for (int k = 0; k < 20000; ++k) {
        const V p = V(0.3, 0.2, 0.1) + V(u(random), u(random), u(random));
        const double r = (p - V(0.3, 0.2, 0.1)).norm();
        if (r > 0.0995 && r < 0.1) continue;
        ++checked;
        if (m.inside(p) != (r < 0.1)) ++wrong;
        // and the distance to the surface
        if (std::abs(r - 0.1) < 0.03) {
            const double d = m.distance(p, 0.04);
            EXPECT_NEAR(d, std::abs(r - 0.1), 0.0006) << r;
        }
    }
    EXPECT_GT(checked, 19000);
    EXPECT_EQ(wrong, 0);
}

// A closed mesh is a Shape as the primitives are: cut out of a fluid box, and a rigid body whose
// volume comes from its lattice points.
TEST(Mesh, ClosedMeshAsSubtractionAndBody) {
    log::setQuiet(true);
    test::TempDir tmp;
    const double R = 0.1;
    const Mesh s = icosphere(R, 3, V(0.3, 0.3, 0.3));
    writeAsciiStl(tmp.path() / "constant/triSurface/ball.stl", s);
    TriangleMesh ball = TriangleMesh::fromTriangles(s.x, s.t);
    ball.prepare();
    const std::size_t inside = latticeInside(ball, Scalar(dx), 3).size();
    const auto cut = sample(tmp.path(), "fluid { water { type box; min (0 0 0); max (0.6 0.6 0.6); subtract { ball { "
                                        "type mesh; file \"ball.stl\"; } } } }", dx, 3);
    EXPECT_EQ(cut.fluidPositions.size(), 30u * 30 * 30 - inside);
    for (const auto& p : cut.fluidPositions) ASSERT_FALSE(ball.inside(p.cast<double>()));
    const auto body = sample(tmp.path(), "fluid { water { type box; min (0.8 0 0); max (1 0.2 0.2); } } bodies { ball "
                                         "{ type mesh; file \"ball.stl\"; layers 2; density 500; } }", dx, 3);
    ASSERT_EQ(body.walls.size(), 1u);
    const double volume = 4.0 / 3 * M_PI * R * R * R;
    std::cout << "mesh body: " << body.walls[0].positions.size() << " particles, volume " << body.walls[0].mass.volume
              << " m^3 vs the sphere's " << volume << " (" << 100 * (body.walls[0].mass.volume / volume - 1)
              << " %), centroid " << body.walls[0].mass.centroid.transpose() << "\n";
    // its volume is its lattice points' (Shape.hpp's rule for every shape but a box): exactly the
    // points inside the mesh, Δx³ each; against the sphere, the lattice's error at R = 5 Δx (+5.4 %)
    EXPECT_NEAR(body.walls[0].mass.volume, double(inside) * dx * dx * dx, 1e-9);
    EXPECT_NEAR(body.walls[0].mass.volume, volume, 0.08 * volume);
    EXPECT_LT((body.walls[0].mass.centroid - V(0.3, 0.3, 0.3)).norm(), 0.1 * dx);
    for (const auto& p : body.walls[0].positions) {
        const double d = ball.distance(p.cast<double>(), 1);
        EXPECT_TRUE(ball.inside(p.cast<double>()));
        EXPECT_LT(d, 2 * dx);
    }
}

struct PoissonFigures {
    double minSpacing = 1e9, covering = 0; // least distance between samples; farthest surface point from one
};

PoissonFigures poissonFigures(const TriangleMesh& m, const std::vector<Vec3>& samples, double r, int dim) {
    PoissonFigures f;
    PointGrid grid(r, dim);
    for (const auto& p : samples) {
        const double d = grid.nearest(p, 1);
        f.minSpacing = std::min(f.minSpacing, d);
        grid.add(p);
    }
    // farthest point of the surface from every sample: dense random points on it (3D) or the
    // section's segments (2D) checked against the samples
    std::mt19937 random(3);
    std::uniform_real_distribution<double> u(0, 1);
    const auto check = [&](const V& q) {
        const Vec3 p = Vec3(Scalar(q[0]), Scalar(q[1]), dim == 3 ? Scalar(q[2]) : Scalar(0));
        f.covering = std::max(f.covering, grid.nearest(p, 2));
    };
    for (const auto& t : m.triangles()) {
        const V a = m.vertices()[t[0]], ab = m.vertices()[t[1]] - a, ac = m.vertices()[t[2]] - a;
        if (dim == 3) {
            const int n = int(400 * 0.5 * ab.cross(ac).norm() / (r * r)) + 3;
            for (int k = 0; k < n; ++k) {
                double s = u(random), q = u(random);
                if (s + q > 1) s = 1 - s, q = 1 - q;
                check(a + s * ab + q * ac);
            }
        } else {
            std::vector<V> ends;
            for (int k = 0; k < 3; ++k) {
                const V& p = m.vertices()[t[k]];
                const V& q = m.vertices()[t[(k + 1) % 3]];
                if ((p[2] >= 0) != (q[2] >= 0)) ends.push_back(p + p[2] / (p[2] - q[2]) * (q - p));
            }
            if (ends.size() == 2)
                for (int k = 0; k <= 400; ++k) check(ends[0] + (k / 400.0) * (ends[1] - ends[0]));
        }
    }
    return f;
}

// Seed 002's wall: the least spacing is the radius r, and no point of the surface is farther than
// r (and the candidates' spacing) from a sample.
TEST(Mesh, PoissonDiskSpacingAndCoverage) {
    const double r = 0.01;
    const Mesh s = icosphere(0.1, 4);
    TriangleMesh sphere = TriangleMesh::fromTriangles(s.x, s.t);
    sphere.prepare();
    const auto samples = poissonDiskSurface(sphere, r, 3).positions;
    const PoissonFigures f = poissonFigures(sphere, samples, r, 3);
    // mean area a sample: 4π R² / n against π r²/4 (disks of radius r/2 around each)
    std::cout << "poissonDisk 3D sphere R = 10 r: " << samples.size() << " samples, least spacing "
              << f.minSpacing / r << " r, coverage (farthest surface point) " << f.covering / r << " r, area a sample "
              << 4 * M_PI * 0.01 / samples.size() / (r * r) << " r^2\n";
    EXPECT_GE(f.minSpacing, r * (1 - test::tol(1e-12, 1e-5)));
    EXPECT_LE(f.covering, 1.1 * r);
    EXPECT_GT(f.covering, 0.5 * r); // (a sampling as dense as the test points would pass anything)

    // 2D: the section of a prism (the open tank of the hydrostatic test)
    const Mesh open = openTankMesh(V(-0.005, -0.005, -1), V(0.205, 0.5, 1));
    TriangleMesh tank = TriangleMesh::fromTriangles(open.x, open.t);
    EXPECT_GT(tank.openEdges(), 0u);
    const auto samples2 = poissonDiskSurface(tank, r, 2).positions;
    const PoissonFigures f2 = poissonFigures(tank, samples2, r, 2);
    std::cout << "poissonDisk 2D tank section: " << samples2.size() << " samples over " << 0.21 + 2 * 0.505
              << " m, least spacing " << f2.minSpacing / r << " r, coverage " << f2.covering / r << " r, mean spacing "
              << (0.21 + 2 * 0.505) / samples2.size() / r << " r\n";
    EXPECT_GE(f2.minSpacing, r * (1 - test::tol(1e-12, 1e-5)));
    EXPECT_LE(f2.covering, 1.05 * r);
    for (const auto& p : samples2) EXPECT_EQ(p[2], 0);
}

void writeCase(const fs::path& dir, const std::string& properties, const std::string& geometry,
               const std::string& control, const std::string& schemes) {
    const auto write = [&](const std::string& rel, const std::string& text) {
        fs::create_directories((dir / rel).parent_path());
        std::ofstream(dir / rel) << "FoamFile { version 2.0; format ascii; class dictionary; object "
                                 << fs::path(rel).filename().string() << "; }\n"
                                 << text;
    };
    write("constant/fluidProperties", properties);
    write("constant/geometry", geometry);
    write("system/controlDict", control);
    write("system/sphSchemes", schemes);
}

// Issue 38's target: fluid filling a closed curved mesh (a sphere of 5120 triangles) shaken for
// 1 s: no fluid particle leaves it.
TEST(Mesh, FluidInAShakenSphereStaysInIt) {
    log::setQuiet(true);
    test::TempDir tmp;
    const V centre(0, 0, 0);
    const double R = 0.1;
    const Mesh s = icosphere(R, 4, centre);
    writeAsciiStl(tmp.path() / "constant/triSurface/ball.stl", s);
    writeCase(tmp.path(),
              "dimension 3; rho0 1000; viscosity 1e-6; gravity (0 -9.81 0); particleSpacing 0.02; supportRadius 2;\n",
              "fluid { water { type mesh; file \"ball.stl\"; } }\n"
              "walls { ball { type mesh; file \"ball.stl\"; side outside; layers 3;\n"
              "   motion { type oscillating; direction (1 0.5 0); amplitude 0.03; period 0.5; } } }\n",
              "application spindrift; startFrom startTime; startTime 0; stopAt endTime; endTime 1; deltaT 1e-4;\n"
              "adjustTimeStep yes; maxCo 0.2; maxDeltaT 1e-3; writeControl adjustableRunTime; writeInterval 1;\n",
              "kernel { type wendlandC2; } pressure { type wcsph; gamma 7; soundSpeed 20; clampNegativePressure yes; }\n"
              "viscosity { type artificial; alpha 0.1; } integrator { type symplecticEuler; } boundary { type adami; }\n");
    Simulation sim(tmp.path());
    const RunSummary run = sim.run();
    const auto& scene = sim.scene();
    const auto& fluid = test::fluidOf(scene);
    ASSERT_GT(fluid.size(), 300u);
    TriangleMesh ball = TriangleMesh::fromTriangles(s.x, s.t);
    ball.prepare();
    const Dictionary motion = Dictionary::fromString("type oscillating; direction (1 0.5 0); amplitude 0.03; period 0.5;");
    const auto m = Motion::read(motion, 3, 0, 1);
    const Vec3 d = m->displacement(run.endTime);
    int outside = 0;
    double farthest = 0;
    for (const auto& x : fluid.particles.position()) {
        const Vec3 local = x - d;
        if (!ball.inside(local.cast<double>())) ++outside;
        farthest = std::max(farthest, double(local.norm()));
    }
    std::cout << "shaken sphere: " << fluid.size() << " fluid particles, " << run.steps << " steps to t = "
              << run.endTime << " s; outside the mesh: " << outside << "; farthest from its centre " << farthest / R
              << " R\n";
    EXPECT_NEAR(run.endTime, 1.0, 1e-9);
    EXPECT_EQ(outside, 0);
}

// The seed's wall on a tank: a Poisson-disk single layer on an open mesh holds still water of
// depth H. Its pressure against ρ0 g H: within 1 % with adami's wall pressure on the layer's
// adaptive volume (chosen by `volume auto` for a wall one layer thick) and the kernel-corrected
// gradient; Akinci's mirrored pressure on the same layer reported, not asserted.
struct PoissonTank {
    double bottomError, gradientError, rowError, rowHeight, top, vMax;
    std::size_t wallParticles;
};

PoissonTank hydrostaticTankOnAPoissonDiskWall(const std::string& boundary, const std::string& pressureOptions,
                                              double endTime) {
    test::TempDir tmp;
    const double h = 0.01, H = 0.2, W = 0.2;
    // the tank's faces half a spacing outside the fluid box [0, W] × [0, H]
    const Mesh open = openTankMesh(V(-h / 2, -h / 2, -1), V(W + h / 2, 0.3, 1));
    writeObj(tmp.path() / "constant/triSurface/tank.obj", open);
    writeCase(tmp.path(),
              "dimension 2; rho0 1000; viscosity 1e-6; gravity (0 -9.81 0); particleSpacing 0.01; supportRadius 3;\n",
              "fluid { water { type box; min (0 0 0); max (0.2 0.2 0); initialPressure hydrostatic; } }\n"
              "walls { tank { type mesh; file \"tank.obj\"; sampling poissonDisk; spacing 0.5; } }\n",
              "application spindrift; startFrom startTime; startTime 0; stopAt endTime; endTime " +
                  std::to_string(endTime) + "; deltaT 1e-4;\n"
              "adjustTimeStep yes; maxCo 0.15; maxDeltaT 1e-3; writeControl adjustableRunTime; writeInterval 1;\n",
              "kernel { type wendlandC2; } pressure { type wcsph; gamma 7; soundSpeed 20; clampNegativePressure yes; "
              "density continuity; " + pressureOptions + " }\nviscosity { type artificial; alpha 0.1; } "
              "integrator { type symplecticEuler; }\nboundary { " + boundary + " } shifting { type particleCollision; }\n");
    Simulation sim(tmp.path());
    const RunSummary run = sim.run();
    EXPECT_NEAR(run.endTime, endTime, 1e-9);
    const auto& fluid = test::fluidOf(sim.scene());
    const double rho0 = 1000, g = 9.81;
    // the pressure at the bottom: the interior's profile p = a + b z (least squares over the
    // particles 3 spacings and more from the walls and the surface) at the floor z = 0, where the
    // fluid box starts (the wall's particles half a spacing below); and the bottom row's own
    double sz = 0, sp = 0, szz = 0, szp = 0, pRow = 0, zRow = 0, top = -1;
    int n = 0, nRow = 0;
    for (std::size_t i = 0; i < fluid.size(); ++i) {
        const auto& x = fluid.particles.position()[i];
        const double p = fluid.particles.pressure()[i], z = x.y();
        top = std::max(top, z);
        EXPECT_GT(x.x(), -h / 2);
        EXPECT_LT(x.x(), W + h / 2);
        EXPECT_GT(x.y(), -h / 2);
        if (x.x() < 3 * h || x.x() > W - 3 * h) continue;
        if (z < h) {
            pRow += p;
            zRow += z;
            ++nRow;
        }
        if (z < 3 * h || z > H - 3 * h) continue;
        sz += z;
        sp += p;
        szz += z * z;
        szp += z * p;
        ++n;
    }
    EXPECT_GT(n, 50);
    EXPECT_GT(nRow, 5);
    const double b = (n * szp - sz * sp) / (n * szz - sz * sz), a = (sp - b * sz) / n;
    pRow /= nRow;
    zRow /= nRow;
    double vMax = 0;
    for (const auto& v : fluid.particles.velocity()) vMax = std::max(vMax, double(v.norm()));
    const PoissonTank r{(a - rho0 * g * H) / (rho0 * g * H), (-b - rho0 * g) / (rho0 * g),
                        (pRow - rho0 * g * (H - zRow)) / (rho0 * g * H), zRow / h, top, vMax,
                        sim.scene().systems[1]->size()};
    std::cout << "hydrostatic tank on a Poisson-disk wall (spacing 0.5), boundary { " << boundary << " } "
              << pressureOptions << ": " << r.wallParticles << " wall particles, " << fluid.size()
              << " fluid particles, " << run.steps << " steps to t = " << run.endTime
              << " s; interior profile at the floor " << 100 * r.bottomError << " % of rho0 g H off it; its gradient "
              << 100 * r.gradientError << " % off rho0 g; the bottom row's own pressure (z = " << r.rowHeight
              << " dx) " << 100 * r.rowError << " % of rho0 g H off hydrostatic; top particle at " << top
              << ", max speed " << vMax << " m/s\n";
    return r;
}

TEST(Mesh, HydrostaticTankOnAPoissonDiskWall) {
    log::setQuiet(true);
    const double h = 0.01, H = 0.2;
    // adami on the layer's adaptive volume (`volume auto` picks it for a wall one layer thick),
    // the kernel-corrected gradient: at 2 s the floor's pressure +0.54 %, the bottom row's own
    // +2.7 % (over 1-3 s: -0.8 to +0.6 % and -2.5 to +3.8 %); with the fluid's mass on every
    // sample (`volume lattice`) the row sat 20 % below hydrostatic
    const PoissonTank adami = hydrostaticTankOnAPoissonDiskWall("type adami;", "gradientCorrection yes;", 2.0);
    EXPECT_LT(std::abs(adami.bottomError), 0.01);
    EXPECT_LT(std::abs(adami.rowError), 0.05);
    // the wall holds the water (at spacing 1 a particle leaked through it and the run stopped):
    // the surface within a spacing of H, slow
    EXPECT_GT(adami.top, H - 2 * h);
    EXPECT_LT(adami.top, H + h);
    EXPECT_LT(adami.vMax, 0.2);
    // Akinci's mirrored pressure on the same layer holds the water but not its pressure: the
    // bottom row pushed off the layer (0.5 to 0.7 dx in 1 s), its own pressure 20-55 % of
    // rho0 g H low, the column oscillating (docs/VALIDATION.md §Meshes). Reported, not asserted.
    const PoissonTank akinci = hydrostaticTankOnAPoissonDiskWall("type akinci; volume adaptive;", "", 1.0);
    EXPECT_GT(akinci.top, H - 2 * h);
    EXPECT_LT(akinci.top, H + h);
}

// `volume auto` of both wall models: a wall sampled in one layer (a Poisson-disk sheet) takes the
// adaptive volume, a lattice wall of three layers the fluid's mass m. In 3D the sheet's kernel sum
// exceeds a full lattice's by its density alone (1.8 times at spacing 0.5): the sheet is told by
// the shape of its neighbourhoods, not their sum.
// A Poisson-disk single layer in 3D: a cube of still water in an open box mesh. The layer's
// share tells neither side nor distance near it, and at a corner its gradient points along the
// other faces: on main before the sheets' collision (WallCollision.hpp) a corner particle crept to
// the floor, went through it at 0.55 s and the run stopped. Read from the layer's surface normals,
// every face of the corner stops it: none comes nearer a face's layer than a quarter spacing.
TEST(Mesh, StillWaterStaysInAPoissonDiskCube3D) {
    log::setQuiet(true);
    test::TempDir tmp;
    const double h = 0.01, L = 0.1;
    const Mesh open = openTankMesh(V(-h / 2, -h / 2, -h / 2), V(L + h / 2, 2 * L, L + h / 2));
    writeObj(tmp.path() / "constant/triSurface/tank.obj", open);
    writeCase(tmp.path(),
              "dimension 3; rho0 1000; viscosity 1e-6; gravity (0 -9.81 0); particleSpacing 0.01; supportRadius 3;\n",
              "fluid { water { type box; min (0 0 0); max (0.1 0.1 0.1); initialPressure hydrostatic; } }\n"
              "walls { tank { type mesh; file \"tank.obj\"; sampling poissonDisk; spacing 0.5; } }\n",
              "application spindrift; startFrom startTime; startTime 0; stopAt endTime; endTime 0.8; deltaT 1e-4;\n"
              "adjustTimeStep yes; maxCo 0.15; maxDeltaT 1e-3; writeControl adjustableRunTime; writeInterval 1;\n",
              "kernel { type wendlandC2; } pressure { type wcsph; gamma 7; soundSpeed 20; clampNegativePressure yes; "
              "density continuity; gradientCorrection yes; }\nviscosity { type artificial; alpha 0.1; } "
              "integrator { type symplecticEuler; }\nboundary { type adami; } shifting { type particleCollision; }\n");
    Simulation sim(tmp.path());
    const RunSummary run = sim.run();
    EXPECT_NEAR(run.endTime, 0.8, 1e-9);
    const auto& x = test::fluidOf(sim.scene()).particles.position();
    double nearest = 1e9; // from a face's layer, in spacings
    for (const auto& p : x)
        for (const double d : {p.x() + h / 2, L + h / 2 - p.x(), p.y() + h / 2, p.z() + h / 2, L + h / 2 - p.z()})
            nearest = std::min(nearest, d / h);
    std::cout << "still water in a Poisson-disk cube (3D): " << x.size() << " particles, " << run.steps
              << " steps to t = " << run.endTime << " s; nearest a layer " << nearest << " dx\n";
    EXPECT_GT(nearest, 0.25 - 1e-6);
}

// The seed's own walls (Duan et al.: relaxed PBF on a Poisson-disk layer with Akinci's volumes)
// and the other incompressible solvers: with Akinci's volume a single layer gave the first fluid
// row 1.22 ρ0 in 3D (the start's density error 44 % at a corner) and every one of them blew up in
// its first step (up to 280 m/s); with the layer's volume scaled so that the first row sums ρ0
// (akinci's κ) each holds the water over 0.1 s (1 s measured), none nearer a face's layer than
// 0.2 spacings (the collision's face is at 0.25).
TEST(Mesh, EveryIncompressibleSolverHoldsStillWaterOnAPoissonDiskLayer3D) {
    log::setQuiet(true);
    const double h = 0.01, L = 0.1;
    const Mesh open = openTankMesh(V(-h / 2, -h / 2, -h / 2), V(L + h / 2, 2 * L, L + h / 2));
    for (const char* solver : {"relaxedPbf", "pbf", "pcisph", "dfsph", "iisph"}) {
        test::TempDir tmp;
        writeObj(tmp.path() / "constant/triSurface/tank.obj", open);
        writeCase(tmp.path(),
                  "dimension 3; rho0 1000; viscosity 1e-6; gravity (0 -9.81 0); particleSpacing 0.01; supportRadius 3;\n",
                  "fluid { water { type box; min (0 0 0); max (0.1 0.1 0.1); } }\n"
                  "walls { tank { type mesh; file \"tank.obj\"; sampling poissonDisk; spacing 0.5; } }\n",
                  "application spindrift; startFrom startTime; startTime 0; stopAt endTime; endTime 0.1; deltaT 1e-4;\n"
                  "adjustTimeStep yes; maxCo 0.15; maxDeltaT 1e-3; writeControl adjustableRunTime; writeInterval 1;\n",
                  std::string("kernel { type wendlandC2; } pressure { type ") + solver + "; }\n"
                  "viscosity { type artificial; alpha 0.1; soundSpeed 20; } integrator { type symplecticEuler; }\n"
                  "boundary { type akinci; } shifting { type particleCollision; }\n");
        Simulation sim(tmp.path());
        const RunSummary run = sim.run();
        EXPECT_NEAR(run.endTime, 0.1, 1e-9) << solver;
        const auto& fluid = test::fluidOf(sim.scene()).particles;
        double nearest = 1e9, fastest = 0; // from a face's layer, in spacings
        for (std::size_t i = 0; i < fluid.size(); ++i) {
            const Vec3& p = fluid.position()[i];
            for (const double d : {p.x() + h / 2, L + h / 2 - p.x(), p.y() + h / 2, p.z() + h / 2, L + h / 2 - p.z()})
                nearest = std::min(nearest, d / h);
            fastest = std::max(fastest, double(fluid.velocity()[i].norm()));
        }
        std::cout << solver << " on a Poisson-disk layer (3D, akinci): " << run.steps << " steps to t = " << run.endTime
                  << " s, max density error " << 100 * run.maxDensityError << " %, nearest a layer " << nearest
                  << " dx, fastest " << fastest << " m/s\n";
        EXPECT_GT(nearest, 0.2) << solver; // (the position-based corrections may end a little inside the face)
        EXPECT_LT(fastest, 0.5) << solver; // still water: a slosh of decimetres a second at most
        EXPECT_EQ(fluid.size(), 1000u) << solver;
    }
}

TEST(Mesh, SingleLayerWallsTakeTheAdaptiveVolume) {
    log::setQuiet(true);
    for (const int dim : {2, 3})
        for (const std::string boundary : {"adami", "akinci"}) {
            test::TempDir tmp;
            const double h = 0.01, W = 0.1;
            const double zlo = dim == 3 ? -h / 2 : -1, zhi = dim == 3 ? W + h / 2 : 1;
            const Mesh open = openTankMesh(V(-h / 2, -h / 2, zlo), V(W + h / 2, 0.2, zhi));
            writeObj(tmp.path() / "constant/triSurface/tank.obj", open);
            const std::string top = dim == 3 ? "0.1 0.1 0.1" : "0.1 0.1 0";
            writeCase(tmp.path(),
                      "dimension " + std::to_string(dim) +
                          "; rho0 1000; viscosity 1e-6; gravity (0 -9.81 0); particleSpacing 0.01; supportRadius 3;\n",
                      "fluid { water { type box; min (0 0 0); max (" + top + "); initialPressure hydrostatic; } }\n"
                      "walls { tank { type mesh; file \"tank.obj\"; sampling poissonDisk; spacing 0.5; }\n"
                      "        lid { type container; min (-0.05 -0.05 " + std::string(dim == 3 ? "-0.05" : "0") +
                          "); max (0.15 0.3 " + std::string(dim == 3 ? "0.15" : "0") + "); } }\n",
                      "application spindrift; startFrom startTime; startTime 0; stopAt endTime; endTime 1e-4; "
                      "deltaT 1e-4;\nwriteControl timeStep; writeInterval 1;\n",
                      "kernel { type wendlandC2; } pressure { type wcsph; gamma 7; soundSpeed 20; density continuity; }\n"
                      "viscosity { type artificial; alpha 0.1; } integrator { type symplecticEuler; }\n"
                      "boundary { type " + boundary + "; }\n");
            Simulation sim(tmp.path());
            sim.run();
            const double m = sim.scene().constants.particleMass;
            const ParticleSystem& sheet = *sim.scene().systems[1];
            const ParticleSystem& lattice = *sim.scene().systems[2];
            ASSERT_EQ(sheet.name(), "tank");
            ASSERT_TRUE(sheet.mass && lattice.mass);
            double sheetMean = 0, least = 1e300, most = 0;
            for (const Scalar M : *sheet.mass) {
                sheetMean += M / m;
                least = std::min(least, double(M) / m);
                most = std::max(most, double(M) / m);
            }
            sheetMean /= double(sheet.size());
            std::cout << dim << "D " << boundary << ": the sheet's masses " << least << " to " << most << " m, mean "
                      << sheetMean << " m (" << sheet.size() << " particles)\n";
            // adaptive: each particle its own, from its neighbourhood (a lattice mass is m on every one)
            EXPECT_GT(most - least, 0.05) << dim << "D " << boundary;
            EXPECT_LT(most, 3.0) << dim << "D " << boundary;
            EXPECT_GT(least, 0.05) << dim << "D " << boundary;
            for (const Scalar M : *lattice.mass) ASSERT_EQ(double(M), m) << dim << "D " << boundary << ": the container";
        }
}

// Bad meshes: the error names the file (and the entry's `file` keyword).
TEST(Mesh, BadMeshesGetClearErrors) {
    log::setQuiet(true);
    test::TempDir tmp;
    const fs::path tri = tmp.path() / "constant/triSurface";
    fs::create_directories(tri);
    std::ofstream(tri / "empty.stl") << "solid empty\nendsolid empty\n";
    std::ofstream(tri / "garbage.stl") << "this is not a mesh\n";
    writeAsciiStl(tri / "cube.stl", boxMesh(V(0, 0, 0), V(0.2, 0.2, 0.2)));
    Mesh open = boxMesh(V(0, 0, 0), V(0.2, 0.2, 0.2));
    open.t.pop_back();
    writeAsciiStl(tri / "open.stl", open);
    Mesh inverted = boxMesh(V(0, 0, 0), V(0.2, 0.2, 0.2));
    for (auto& t : inverted.t) std::swap(t[1], t[2]);
    writeAsciiStl(tri / "inverted.stl", inverted);
    Mesh mixed = boxMesh(V(0, 0, 0), V(0.2, 0.2, 0.2));
    std::swap(mixed.t[0][1], mixed.t[0][2]);
    writeAsciiStl(tri / "mixed.stl", mixed);
    const auto expectError = [&](const std::string& geometry, const std::string& pattern, int dim = 3) {
        try {
            sample(tmp.path(), geometry, dx, dim);
            ADD_FAILURE() << "no error for: " << geometry;
        } catch (const InputError& e) {
            const std::string text = locatedMessage(e.where(), "error", e.message());
            EXPECT_NE(text.find("geometry:1:"), std::string::npos) << text;
            EXPECT_NE(text.find(pattern), std::string::npos) << text;
            EXPECT_EQ(e.keyword(), "file") << text;
        }
    };
    const auto fluidMesh = [](const std::string& f) { return "fluid { water { type mesh; file \"" + f + "\"; } }"; };
    expectError(fluidMesh("missing.stl"), "cannot read mesh file '" + (tri / "missing.stl").string() + "': no such file");
    expectError(fluidMesh("garbage.stl"), "cannot read mesh file '" + (tri / "garbage.stl").string() + "'");
    expectError(fluidMesh("empty.stl"), "empty.stl");
    expectError(fluidMesh("open.stl"), "open.stl' is not closed: 3 of its edges");
    expectError(fluidMesh("inverted.stl"), "inverted.stl' has inverted normals: its enclosed volume is -0.008");
    expectError(fluidMesh("mixed.stl"), "mixed.stl' is not consistently oriented");
    expectError("fluid { water { type box; min (0 0 0); max (0.1 0.1 0.1); } } walls { w { type mesh; file "
                "\"open.stl\"; layers 2; } }",
                "open.stl' is not closed");
    // far outside: a tank in millimetres
    expectError("fluid { water { type box; min (0 0 0); max (0.1 0.1 0.1); } } walls { w { type mesh; file "
                "\"cube.stl\"; translate (100 0 0); } }",
                "cube.stl' of wall 'w' lies far outside the domain");
    expectError("fluid { water { type mesh; file \"cube.stl\"; translate (0 0 1); } }", "does not cross the plane z = 0", 2);
    // a Poisson-disk wall takes an open mesh
    const auto ok = sample(tmp.path(), "fluid { water { type box; min (0.3 0 0); max (0.4 0.1 0.1); } } walls { w { "
                                       "type mesh; file \"open.stl\"; sampling poissonDisk; } }", dx, 3);
    EXPECT_GT(ok.walls[0].positions.size(), 100u);
}

} // namespace
