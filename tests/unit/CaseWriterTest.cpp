// Tests of CaseWriter: time names, .vtp round trip at full precision, field selection, time
// directories written atomically and the .pvd collection.
#include "CaseWriter.hpp"
#include "TestSupport.hpp"

#include <gtest/gtest.h>

#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLPolyDataReader.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

namespace fs = std::filesystem;
using namespace spindrift;
using spindrift::test::TempDir;

namespace {

ParticleSet randomSet(std::size_t n, unsigned seed, const std::string& name = "fluid") {
    ParticleSet set(name);
    set.resize(n);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    auto r = [&] { return static_cast<Scalar>(u(rng)); };
    auto rv = [&] { return Vec3(r(), r(), r()); };
    auto& smoothing = set.addScalar("smoothingLength");
    auto& vorticity = set.addVector("vorticity");
    for (std::size_t i = 0; i < n; ++i) {
        set.position()[i] = rv();
        set.velocity()[i] = rv();
        set.density()[i] = 1000 + 10 * r();
        set.pressure()[i] = 1e5 * r();
        set.id()[i] = static_cast<Index>(1000000 + 7 * i);
        smoothing[i] = r() * Scalar(1e-3);
        vorticity[i] = rv();
    }
    set.setParticleMass(Scalar(0.0123456789));
    return set;
}

// One <DataSet> of the collection.
struct PvdEntry {
    std::string timestep, part, file, name;
};

std::vector<PvdEntry> parsePvd(const fs::path& file) {
    vtkNew<vtkXMLDataParser> parser;
    parser->SetFileName(file.string().c_str());
    EXPECT_EQ(parser->Parse(), 1) << file;
    std::vector<PvdEntry> entries;
    vtkXMLDataElement* root = parser->GetRootElement();
    if (!root) return entries;
    EXPECT_STREQ(root->GetName(), "VTKFile");
    EXPECT_STREQ(root->GetAttribute("type"), "Collection");
    vtkXMLDataElement* collection = root->FindNestedElementWithName("Collection");
    if (!collection) {
        ADD_FAILURE() << "no <Collection> in " << file;
        return entries;
    }
    for (int i = 0; i < collection->GetNumberOfNestedElements(); ++i) {
        vtkXMLDataElement* e = collection->GetNestedElement(i);
        EXPECT_STREQ(e->GetName(), "DataSet");
        auto attr = [&](const char* a) {
            const char* v = e->GetAttribute(a);
            return std::string(v ? v : "");
        };
        entries.push_back({attr("timestep"), attr("part"), attr("file"), attr("name")});
    }
    return entries;
}

std::vector<std::string> pointArrayNames(const fs::path& file) {
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName(file.string().c_str());
    reader->Update();
    std::vector<std::string> names;
    vtkPointData* pd = reader->GetOutput()->GetPointData();
    for (int i = 0; i < pd->GetNumberOfArrays(); ++i) names.emplace_back(pd->GetArrayName(i));
    return names;
}

bool contains(const std::vector<std::string>& v, const std::string& s) {
    return std::find(v.begin(), v.end(), s) != v.end();
}

std::vector<std::string> namesOf(const std::vector<std::pair<double, std::string>>& times) {
    std::vector<std::string> names;
    for (auto& t : times) names.push_back(t.second);
    return names;
}

} // namespace

TEST(CaseWriter, TimeNameIsOpenFoamGeneralFormat) {
    EXPECT_EQ(CaseWriter::timeName(0), "0");
    EXPECT_EQ(CaseWriter::timeName(-0.0), "0");
    EXPECT_EQ(CaseWriter::timeName(0.05), "0.05");
    EXPECT_EQ(CaseWriter::timeName(1e-05), "1e-05");
    EXPECT_EQ(CaseWriter::timeName(1.25), "1.25");
    EXPECT_EQ(CaseWriter::timeName(0.30000000000000004), "0.3");
    EXPECT_EQ(CaseWriter::timeName(0.1 + 0.2), "0.3");
    EXPECT_EQ(CaseWriter::timeName(2.0), "2");
    EXPECT_EQ(CaseWriter::timeName(100), "100");
    EXPECT_EQ(CaseWriter::timeName(1234567.0), "1.23457e+06");
    EXPECT_EQ(CaseWriter::timeName(1234567.0, 8), "1234567");
    EXPECT_EQ(CaseWriter::timeName(0.123456789, 3), "0.123");
    EXPECT_EQ(CaseWriter::timeName(0.123456789, 9), "0.123456789");
}

TEST(CaseWriter, VtpRoundTripIsExact) {
    TempDir dir("spindrift-casewriter");
    const ParticleSet set = randomSet(317, 42);
    const fs::path file = dir.path() / "fluid.vtp";
    writeVtp(file, set);
    ASSERT_TRUE(fs::is_regular_file(file));

    // Raw binary appended, no compression, no base64.
    const std::string text = test::readFile(file);
    EXPECT_NE(text.find("<AppendedData encoding=\"raw\">"), std::string::npos);
    EXPECT_EQ(text.find("compressor="), std::string::npos);
    EXPECT_NE(text.find("Name=\"id\""), std::string::npos);
    EXPECT_NE(text.find("type=\"UInt32\""), std::string::npos);

    const ParticleSet back = readVtp(file);
    EXPECT_EQ(back.name(), "fluid");
    ASSERT_EQ(back.size(), set.size());
    const auto* smoothing = back.findScalar("smoothingLength");
    const auto* vorticity = back.findVector("vorticity");
    ASSERT_NE(smoothing, nullptr);
    ASSERT_NE(vorticity, nullptr);
    EXPECT_EQ(back.findVector("position"), &back.position()); // not a second "position"
    EXPECT_EQ(back.findScalar("density"), &back.density());
    EXPECT_EQ(back.findVector("velocity"), &back.velocity());
    for (std::size_t i = 0; i < set.size(); ++i) {
        EXPECT_EQ(back.id()[i], set.id()[i]);
        for (int k = 0; k < 3; ++k) {
            EXPECT_EQ(back.position()[i][k], set.position()[i][k]);
            EXPECT_EQ(back.velocity()[i][k], set.velocity()[i][k]);
            EXPECT_EQ((*vorticity)[i][k], (*set.findVector("vorticity"))[i][k]);
        }
        EXPECT_EQ(back.density()[i], set.density()[i]);
        EXPECT_EQ(back.pressure()[i], set.pressure()[i]);
        EXPECT_EQ((*smoothing)[i], (*set.findScalar("smoothingLength"))[i]);
    }
    EXPECT_EQ(back.particleMass(), set.particleMass());
    // acceleration is restart data (not output): written, and read back exactly.
    EXPECT_TRUE(contains(pointArrayNames(file), "acceleration"));
    EXPECT_EQ(back.acceleration(), set.acceleration());
}

TEST(CaseWriter, VtpHasOneVertexPerParticleAndScalarTypedArrays) {
    TempDir dir("spindrift-casewriter");
    const ParticleSet set = randomSet(50, 3);
    const fs::path file = dir.path() / "fluid.vtp";
    writeVtp(file, set);
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName(file.string().c_str());
    reader->Update();
    vtkPolyData* poly = reader->GetOutput();
    ASSERT_EQ(poly->GetNumberOfPoints(), 50);
    EXPECT_EQ(poly->GetNumberOfVerts(), 50);
    EXPECT_EQ(poly->GetNumberOfCells(), 50);
    const int expected = std::is_same_v<Scalar, double> ? VTK_DOUBLE : VTK_FLOAT;
    EXPECT_EQ(poly->GetPoints()->GetDataType(), expected);
    EXPECT_EQ(poly->GetPointData()->GetArray("density")->GetDataType(), expected);
    EXPECT_EQ(poly->GetPointData()->GetArray("velocity")->GetNumberOfComponents(), 3);
    EXPECT_EQ(poly->GetPointData()->GetArray("id")->GetDataType(), VTK_UNSIGNED_INT);
}

TEST(CaseWriter, EmptySetRoundTrips) {
    TempDir dir("spindrift-casewriter");
    ParticleSet set("boundary");
    writeVtp(dir.path() / "empty.vtp", set);
    EXPECT_EQ(readVtp(dir.path() / "empty.vtp", "boundary").size(), 0u);
}

TEST(CaseWriter, FieldSelection) {
    TempDir dir("spindrift-casewriter");
    ParticleSet set = randomSet(20, 7);
    set.addScalar("notOutput", {false, false});
    set.addScalar("restartOnly", {false, true});
    set.addVector("wallNormal", {true, false});

    // Default selection: every field flagged output, plus restart fields.
    writeVtp(dir.path() / "all.vtp", set);
    auto all = pointArrayNames(dir.path() / "all.vtp");
    EXPECT_TRUE(contains(all, "id"));
    EXPECT_TRUE(contains(all, "velocity"));
    EXPECT_TRUE(contains(all, "density"));
    EXPECT_TRUE(contains(all, "pressure"));
    EXPECT_TRUE(contains(all, "smoothingLength"));
    EXPECT_TRUE(contains(all, "wallNormal"));
    EXPECT_TRUE(contains(all, "restartOnly"));
    EXPECT_FALSE(contains(all, "notOutput"));
    EXPECT_TRUE(contains(all, "acceleration")); // restart data
    EXPECT_FALSE(contains(all, "position"));

    // Explicit selection: the names given, restart fields anyway, id always.
    writeVtp(dir.path() / "some.vtp", set, {"acceleration", "notOutput"});
    auto some = pointArrayNames(dir.path() / "some.vtp");
    EXPECT_TRUE(contains(some, "id"));
    EXPECT_TRUE(contains(some, "acceleration"));
    EXPECT_TRUE(contains(some, "notOutput"));
    EXPECT_TRUE(contains(some, "restartOnly"));
    EXPECT_TRUE(contains(some, "velocity")); // restart
    EXPECT_TRUE(contains(some, "density"));  // restart
    EXPECT_FALSE(contains(some, "smoothingLength"));
    EXPECT_FALSE(contains(some, "wallNormal"));
    EXPECT_FALSE(contains(some, "position"));

    // Without restart fields (a wall's .vtp): only what is selected.
    writeVtp(dir.path() / "view.vtp", set, {"pressure"}, false);
    EXPECT_EQ(pointArrayNames(dir.path() / "view.vtp"), (std::vector<std::string>{"id", "pressure"}));
    writeVtp(dir.path() / "viewAll.vtp", set, {}, false);
    auto view = pointArrayNames(dir.path() / "viewAll.vtp");
    EXPECT_TRUE(contains(view, "velocity"));
    EXPECT_TRUE(contains(view, "wallNormal"));
    EXPECT_FALSE(contains(view, "acceleration")) << "restart data only";
    EXPECT_FALSE(contains(view, "restartOnly"));
}

TEST(CaseWriter, FieldOfWrongSizeIsSkipped) {
    TempDir dir("spindrift-casewriter");
    ParticleSet set = randomSet(10, 1);
    set.addScalar("broken").resize(3);
    writeVtp(dir.path() / "f.vtp", set);
    EXPECT_FALSE(contains(pointArrayNames(dir.path() / "f.vtp"), "broken"));
}

TEST(CaseWriter, WriteFailureNamesTheFile) {
    TempDir dir("spindrift-casewriter");
    const fs::path file = dir.path() / "no" / "such" / "dir" / "fluid.vtp";
    try {
        writeVtp(file, randomSet(5, 1));
        FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    }
    EXPECT_THROW(readVtp(dir.path() / "missing.vtp"), std::runtime_error);
    dir.writeFile("garbage.vtp", "this is not XML");
    EXPECT_THROW(readVtp(dir.path() / "garbage.vtp"), std::runtime_error);

    // A truncated file (crash while writing outside CaseWriter) is an error, not zeros.
    const fs::path truncated = dir.path() / "truncated.vtp";
    writeVtp(truncated, randomSet(100, 2));
    fs::resize_file(truncated, fs::file_size(truncated) - 500);
    try {
        readVtp(truncated);
        FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("truncated.vtp"), std::string::npos) << e.what();
    }
}

// Every time directory holds every system the writer was given (a wall's pressure changes, and
// a time directory is whole by itself); the .pvd points each block of a time at its own file.
TEST(CaseWriter, TimesWithWalls) {
    TempDir dir("spindrift-casewriter");
    const fs::path caseDir = dir.path() / "damBreak";
    CaseWriter writer(caseDir);
    const ParticleSet fluid = randomSet(100, 11);
    const ParticleSet walls = randomSet(40, 12, "boundary");
    writer.write(0.0, fluid, {&walls});
    writer.write(0.05, fluid, {&walls});
    writer.write(0.1 + 1e-17, fluid, {&walls});

    EXPECT_EQ(writer.collectionFile(), caseDir / "damBreak.pvd");
    for (const char* t : {"0", "0.05", "0.1"}) {
        EXPECT_TRUE(fs::is_regular_file(caseDir / t / "fluid.vtp")) << t;
        EXPECT_TRUE(fs::is_regular_file(caseDir / t / "boundary.vtp")) << t;
    }
    for (const auto& e : fs::directory_iterator(caseDir)) {
        const std::string name = e.path().filename().string();
        EXPECT_EQ(name.find(".tmp"), std::string::npos) << "leftover " << name;
        EXPECT_EQ(name.find(".old"), std::string::npos) << "leftover " << name;
    }
    EXPECT_EQ(namesOf(writer.existingTimes()), (std::vector<std::string>{"0", "0.05", "0.1"}));
    EXPECT_EQ(writer.timesWritten(), 3u);

    const auto entries = parsePvd(writer.collectionFile());
    ASSERT_EQ(entries.size(), 6u);
    int fluidCount = 0, boundaryCount = 0;
    for (const auto& e : entries) {
        if (e.part == "0") {
            ++fluidCount;
            EXPECT_EQ(e.file, e.timestep + "/fluid.vtp");
            EXPECT_EQ(e.name, "fluid");
        } else {
            ++boundaryCount;
            EXPECT_EQ(e.part, "1");
            EXPECT_EQ(e.file, e.timestep + "/boundary.vtp");
            EXPECT_EQ(e.name, "boundary");
        }
        EXPECT_TRUE(fs::is_regular_file(caseDir / e.file)) << e.file; // relative paths
    }
    EXPECT_EQ(fluidCount, 3);
    EXPECT_EQ(boundaryCount, 3);
    EXPECT_EQ(entries[0].timestep, "0");
    EXPECT_EQ(entries[2].timestep, "0.05");
    EXPECT_EQ(entries[4].timestep, "0.1");
    EXPECT_FALSE(fs::exists(caseDir / "damBreak.pvd.tmp"));

    // Keep a copy for the ParaView check (tests/cases/pvpython_check.py), when asked.
    if (const char* keep = std::getenv("SPINDRIFT_KEEP_CASE")) {
        fs::remove_all(keep);
        fs::copy(caseDir, keep, fs::copy_options::recursive);
    }
}

// A wall is listed at the times that hold it, under one part number throughout (a wall added or
// taken out at a restart: issue 33, item 7).
TEST(CaseWriter, EachTimeListsTheSystemsItHolds) {
    TempDir dir("spindrift-casewriter");
    const fs::path caseDir = dir.path() / "paddle";
    CaseWriter writer(caseDir);
    const ParticleSet fluid = randomSet(10, 1);
    const ParticleSet tank = randomSet(5, 2, "tank"), paddle = randomSet(4, 3, "paddle");
    writer.write(0.0, fluid, {&tank});
    writer.write(0.5, fluid, {&tank, &paddle});
    writer.write(1.0, fluid, {&paddle});
    std::vector<std::string> parts;
    for (const auto& e : parsePvd(writer.collectionFile())) {
        parts.push_back(e.timestep + " " + e.part + " " + e.name + " " + e.file);
        EXPECT_TRUE(fs::is_regular_file(caseDir / e.file)) << e.file;
    }
    EXPECT_EQ(parts, (std::vector<std::string>{"0 0 fluid 0/fluid.vtp", "0 2 tank 0/tank.vtp",
                                               "0.5 0 fluid 0.5/fluid.vtp", "0.5 1 paddle 0.5/paddle.vtp",
                                               "0.5 2 tank 0.5/tank.vtp", "1 0 fluid 1/fluid.vtp",
                                               "1 1 paddle 1/paddle.vtp"}));
    // a restart from the newest time scans the same blocks back
    CaseWriter again(caseDir);
    again.beginRun(1.0, "1");
    std::vector<std::string> scanned;
    for (const auto& e : parsePvd(again.collectionFile())) scanned.push_back(e.timestep + " " + e.part + " " + e.name + " " + e.file);
    EXPECT_EQ(scanned, parts);
}

// Only canonical names of times (what timeName gives at some precision), not before the
// earliest time, are times (issue 33, item 4: " 0.025", "0x1p-6" and "-1" were listed).
TEST(CaseWriter, ExistingTimesIgnoresIncompleteHiddenAndNonCanonical) {
    TempDir dir("spindrift-casewriter");
    const fs::path caseDir = dir.path() / "c";
    CaseWriter writer(caseDir);
    const ParticleSet fluid = randomSet(10, 5);
    writer.write(0.1, fluid, {});
    writer.write(0.0, fluid, {});
    writer.write(1e-05, fluid, {});
    writer.write(10.0, fluid, {});
    writer.write(2.0, fluid, {});

    const auto timeLike = [&](const std::string& name) {
        fs::create_directories(caseDir / name);
        fs::copy_file(caseDir / "0" / "fluid.vtp", caseDir / name / "fluid.vtp");
    };
    timeLike(".0.2.tmp");
    fs::create_directories(caseDir / "0.3"); // incomplete
    for (const char* name : {"constant", "0.4abc", " 0.025", "0x1p-6", "-1", "0.0250", "+1", "1e1", "inf", "nan"})
        timeLike(name);
    std::ofstream(caseDir / "5") << "a file, not a directory";
    fs::create_directory_symlink(caseDir / "nowhere", caseDir / "7"); // dangling

    const auto times = writer.existingTimes();
    EXPECT_EQ(namesOf(times), (std::vector<std::string>{"0", "1e-05", "0.1", "2", "10"}));
    ASSERT_EQ(times.size(), 5u);
    EXPECT_EQ(times[1].first, 1e-05);
    EXPECT_EQ(times[4].first, 10.0);
    double value = 0;
    EXPECT_TRUE(writer.isTimeName("0.025", value));
    EXPECT_EQ(value, 0.025);
    EXPECT_FALSE(writer.isTimeName("-1", value));
    EXPECT_TRUE(CaseWriter(caseDir, 6, -2).isTimeName("-1", value)) << "a case that starts at -2 has time -1";

    // The collection is sorted by value too.
    std::vector<std::string> listed;
    for (const auto& e : parsePvd(writer.collectionFile())) listed.push_back(e.timestep);
    EXPECT_EQ(listed, (std::vector<std::string>{"0", "1e-05", "0.1", "2", "10"}));
}

// A restart continues the complete times up to the one it restarts from: a time deleted meanwhile
// is not listed, one left half-written (.1.5.tmp) is replaced by the new write.
TEST(CaseWriter, ARestartListsTheContinuedTimesPresent) {
    TempDir dir("spindrift-casewriter");
    const fs::path caseDir = dir.path() / "c";
    const ParticleSet fluid = randomSet(10, 5);
    const ParticleSet walls = randomSet(5, 6, "boundary");
    {
        CaseWriter writer(caseDir);
        writer.write(0.0, fluid, {&walls});
        writer.write(0.5, fluid, {&walls});
        writer.write(1.0, fluid, {&walls});
    }
    fs::remove_all(caseDir / "0.5");
    fs::create_directories(caseDir / ".1.5.tmp"); // as left by a crash

    CaseWriter writer(caseDir); // a new run (restart)
    const auto start = writer.beginRun(1.0, "1");
    EXPECT_TRUE(start.movedAside.empty());
    const auto entries = parsePvd(writer.collectionFile());
    ASSERT_EQ(entries.size(), 4u);
    EXPECT_EQ(entries[0].file, "0/fluid.vtp");
    EXPECT_EQ(entries[1].file, "0/boundary.vtp");
    EXPECT_EQ(entries[2].file, "1/fluid.vtp");
    EXPECT_EQ(entries[3].file, "1/boundary.vtp");

    writer.write(1.5, fluid, {&walls});
    EXPECT_FALSE(fs::exists(caseDir / ".1.5.tmp"));
    const auto after = parsePvd(writer.collectionFile());
    ASSERT_EQ(after.size(), 6u);
    EXPECT_EQ(after[4].file, "1.5/fluid.vtp");
    EXPECT_EQ(after[5].file, "1.5/boundary.vtp");
    EXPECT_EQ(writer.timesWritten(), 1u) << "this run's";
}

// A run from startTime owns the case's times (issue 33, item 4): every entry named as a time from
// startTime on — an earlier run's results, a dangling link — goes to previousRun/ (replacing the
// one of an earlier start) and the .pvd lists nothing of them; earlier times stay, unlisted; a
// restart moves the times after the one it continues. Names that are not times stay.
TEST(CaseWriter, AFreshRunMovesTheLaterTimesAside) {
    TempDir dir("spindrift-casewriter");
    const fs::path caseDir = dir.path() / "c";
    const ParticleSet fluid = randomSet(10, 5);
    const auto earlierRun = [&](std::initializer_list<double> times) {
        CaseWriter writer(caseDir);
        for (double t : times) writer.write(t, fluid, {});
    };
    earlierRun({0, 0.01, 0.02, 0.03});
    fs::create_directory_symlink(caseDir / "nowhere", caseDir / "0.04");
    fs::create_directories(caseDir / " 0.025");
    {
        CaseWriter writer(caseDir);
        const auto start = writer.beginRun(0.02);
        EXPECT_EQ(start.movedAside, (std::vector<std::string>{"0.02", "0.03", "0.04"}));
        EXPECT_EQ(start.notListed, (std::vector<std::string>{"0", "0.01"}));
        EXPECT_FALSE(start.replacedPreviousRun);
        EXPECT_TRUE(parsePvd(writer.collectionFile()).empty());
        EXPECT_TRUE(fs::is_regular_file(caseDir / "previousRun/0.03/fluid.vtp"));
        EXPECT_TRUE(fs::is_symlink(caseDir / "previousRun/0.04"));
        EXPECT_TRUE(fs::is_directory(caseDir / " 0.025")) << "not a time: left alone";
        writer.write(0.02, fluid, {});
        std::vector<std::string> files;
        for (const auto& e : parsePvd(writer.collectionFile())) files.push_back(e.file);
        EXPECT_EQ(files, (std::vector<std::string>{"0.02/fluid.vtp"}));
    }
    // a second fresh start replaces previousRun/
    {
        CaseWriter writer(caseDir);
        const auto start = writer.beginRun(0);
        EXPECT_EQ(start.movedAside, (std::vector<std::string>{"0", "0.01", "0.02"}));
        EXPECT_TRUE(start.replacedPreviousRun);
        EXPECT_FALSE(fs::exists(caseDir / "previousRun/0.03"));
        EXPECT_TRUE(fs::exists(caseDir / "previousRun/0.02"));
    }
    // a restart continues 0.01 and moves what is after it
    earlierRun({0, 0.01, 0.02});
    {
        CaseWriter writer(caseDir);
        const auto start = writer.beginRun(0.01 + 1e-17, "0.01");
        EXPECT_EQ(start.movedAside, (std::vector<std::string>{"0.02"}));
        EXPECT_TRUE(start.notListed.empty());
        std::vector<std::string> files;
        for (const auto& e : parsePvd(writer.collectionFile())) files.push_back(e.file);
        EXPECT_EQ(files, (std::vector<std::string>{"0/fluid.vtp", "0.01/fluid.vtp"}));
    }
}

TEST(CaseWriter, WritingTheSameTimeTwiceReplacesIt) {
    TempDir dir("spindrift-casewriter");
    const fs::path caseDir = dir.path() / "c";
    CaseWriter writer(caseDir);
    const ParticleSet walls = randomSet(5, 6, "boundary");
    writer.write(0.0, randomSet(10, 1), {&walls});
    writer.write(0.25, randomSet(10, 1), {&walls});
    std::ofstream(caseDir / "0.25" / "stale.txt") << "from the first write";
    writer.write(0.25, randomSet(20, 2), {});
    EXPECT_EQ(readVtp(caseDir / "0.25" / "fluid.vtp").size(), 20u);
    EXPECT_FALSE(fs::exists(caseDir / "0.25" / "stale.txt"));
    EXPECT_FALSE(fs::exists(caseDir / "0.25" / "boundary.vtp")) << "the time is what the last write gave";
    EXPECT_FALSE(fs::exists(caseDir / ".0.25.old"));
    EXPECT_EQ(parsePvd(writer.collectionFile()).size(), 3u);
    EXPECT_EQ(writer.timesWritten(), 2u);
}

// A name taken by a dangling link or a file (issue 33, item 21: "cannot rename: Not a
// directory") is replaced by the time written.
TEST(CaseWriter, WritesOverADanglingLinkOrAFile) {
    TempDir dir("spindrift-casewriter");
    const fs::path caseDir = dir.path() / "c";
    fs::create_directories(caseDir);
    fs::create_directory_symlink(caseDir / "nowhere", caseDir / "0.01");
    std::ofstream(caseDir / "0.02") << "a file";
    CaseWriter writer(caseDir);
    writer.write(0.01, randomSet(10, 1), {});
    writer.write(0.02, randomSet(10, 1), {});
    EXPECT_TRUE(fs::is_directory(fs::symlink_status(caseDir / "0.01")));
    EXPECT_EQ(readVtp(caseDir / "0.01" / "fluid.vtp").size(), 10u);
    EXPECT_EQ(readVtp(caseDir / "0.02" / "fluid.vtp").size(), 10u);
    EXPECT_FALSE(fs::exists(fs::symlink_status(caseDir / ".0.01.old")));
    EXPECT_FALSE(fs::exists(caseDir / ".0.02.old"));
}

TEST(CaseWriter, CollectionNameFromDotOrTrailingSlash) {
    TempDir dir("spindrift-casewriter");
    const fs::path caseDir = dir.path() / "myCase";
    fs::create_directories(caseDir);
    EXPECT_EQ(CaseWriter(caseDir.string() + "/").collectionFile().filename(), "myCase.pvd");
    EXPECT_EQ(CaseWriter(caseDir / ".").collectionFile().filename(), "myCase.pvd");

    const fs::path previous = fs::current_path();
    fs::current_path(caseDir);
    CaseWriter writer(".");
    EXPECT_EQ(writer.collectionFile().filename(), "myCase.pvd");
    writer.write(0.0, randomSet(5, 1), {});
    fs::current_path(previous);
    EXPECT_TRUE(fs::is_regular_file(caseDir / "myCase.pvd"));
    EXPECT_TRUE(fs::is_regular_file(caseDir / "0" / "fluid.vtp"));
}

TEST(CaseWriter, CaseDirectoryCanBeMoved) {
    TempDir dir("spindrift-casewriter");
    {
        CaseWriter writer(dir.path() / "a");
        writer.write(0.0, randomSet(5, 1), {});
        writer.write(0.1, randomSet(5, 1), {});
    }
    fs::rename(dir.path() / "a", dir.path() / "b");
    for (const auto& e : parsePvd(dir.path() / "b" / "a.pvd"))
        EXPECT_TRUE(fs::is_regular_file(dir.path() / "b" / e.file)) << e.file;
}

// Two different times of one name at the precision (issue 21: at timePrecision 1, 0.1 ended up
// holding t = 0.12): the second is refused and the first kept.
TEST(CaseWriter, ASecondTimeOfTheSameNameIsRefused) {
    TempDir dir("spindrift-casewriter");
    const fs::path caseDir = dir.path() / "c";
    CaseWriter writer(caseDir, 1);
    writer.write(0.1, randomSet(10, 1), {});
    try {
        writer.write(0.12, randomSet(20, 2), {});
        FAIL() << "0.12 written over 0.1";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("both have the name '0.1' at timePrecision 1"), std::string::npos) << e.what();
    }
    EXPECT_EQ(readVtp(caseDir / "0.1" / "fluid.vtp").size(), 10u);
    writer.write(0.1, randomSet(30, 3), {}); // the same time again (a signal's write) replaces it
    EXPECT_EQ(readVtp(caseDir / "0.1" / "fluid.vtp").size(), 30u);
}

// A blow-up's roll-back: the times this writer wrote after the good state go, from the .pvd
// first; times of an earlier run and the good state itself stay.
TEST(CaseWriter, RemovesTheTimesItWroteAfterAGivenTime) {
    TempDir dir("spindrift-casewriter");
    const fs::path caseDir = dir.path() / "c";
    { CaseWriter(caseDir).write(5.0, randomSet(10, 1), {}); } // an earlier run's
    CaseWriter writer(caseDir);
    const ParticleSet walls = randomSet(5, 6, "boundary");
    writer.write(0.0, randomSet(10, 1), {&walls});
    writer.write(0.5, randomSet(10, 1), {&walls});
    writer.write(1.0, randomSet(10, 1), {&walls});
    writer.write(1.5, randomSet(10, 1), {&walls});
    EXPECT_EQ(writer.timesWritten(), 4u);
    EXPECT_EQ(writer.removeTimesWrittenAfter(0.5), (std::vector<std::string>{"1", "1.5"}));
    EXPECT_EQ(writer.timesWritten(), 2u);
    EXPECT_TRUE(fs::exists(caseDir / "0.5"));
    EXPECT_FALSE(fs::exists(caseDir / "1"));
    EXPECT_FALSE(fs::exists(caseDir / "1.5"));
    EXPECT_FALSE(fs::exists(caseDir / ".1.removed"));
    EXPECT_TRUE(fs::exists(caseDir / "5")) << "not written by this writer";
    std::vector<std::string> files;
    for (const auto& e : parsePvd(writer.collectionFile())) files.push_back(e.file);
    EXPECT_EQ(files, (std::vector<std::string>{"0/fluid.vtp", "0/boundary.vtp", "0.5/fluid.vtp", "0.5/boundary.vtp"}));
    EXPECT_TRUE(writer.removeTimesWrittenAfter(0.5).empty());
}
