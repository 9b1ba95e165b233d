// Spindrift — case output: VTK XML PolyData per set and time, .pvd collection at the root.
//
// File layout (see CaseWriter.hpp):
//   <case>/<time>/fluid.vtp, <case>/<time>/<system>.vtp (each other system written that time),
//   <case>/<time>/<block>.vtp (each block of a function object),
//   <case>/<caseName>.pvd listing every complete time with relative paths, a part per system.
// Arrays in a .vtp: points = positions; point data "id" (vtkTypeUInt32Array, i.e. VTK's
// "UInt32", the type of Index), then the selected scalar (1 component) and vector
// (3 components) fields as vtkDoubleArray (vtkFloatArray with SPINDRIFT_SINGLE_PRECISION);
// field data "particleMass" (1 value, same type) so that a restart gets the mass back.
#include "CaseWriter.hpp"

#include "Error.hpp"
#include "Log.hpp"

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <map>

#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkTypeUInt32Array.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <type_traits>

namespace fs = std::filesystem;

namespace spindrift {

namespace {

using VtkScalarArray =
    std::conditional_t<std::is_same_v<Scalar, double>, vtkDoubleArray, vtkFloatArray>;
constexpr int vtkScalarType = std::is_same_v<Scalar, double> ? VTK_DOUBLE : VTK_FLOAT;

// Collects the error messages VTK objects emit (instead of letting VTK print them to stderr),
// so that a failure becomes one std::runtime_error with VTK's own words in it. Keeps the text
// of each message without VTK's "ERROR: In <source>, line <n> <class> (<address>): " prefix;
// the executive's generic "returned failure for request" only when nothing better was said.
class ErrorCollector : public vtkCommand {
public:
    static ErrorCollector* New() { return new ErrorCollector; }
    void Execute(vtkObject*, unsigned long, void* callData) override {
        std::string text = callData ? static_cast<const char*>(callData) : "unknown VTK error";
        if (auto colon = text.find("): "); colon != std::string::npos) text.erase(0, colon + 3);
        if (auto newline = text.find_first_of("\r\n"); newline != std::string::npos)
            text.erase(newline);
        if (text.find("returned failure for request") != std::string::npos) {
            if (generic.empty()) generic = text;
            return;
        }
        if (!specific.empty()) specific += "; ";
        specific += text;
    }
    bool any() const { return !specific.empty() || !generic.empty(); }
    std::string message() const { return specific.empty() ? generic : specific; }

private:
    std::string specific, generic;
};

bool selected(const std::string& name, const FieldOptions& options,
              const std::vector<std::string>& fieldNames, bool restartFields) {
    if (options.scratch || options.undefined) return false;
    if (options.restart && restartFields) return true;
    if (fieldNames.empty()) return options.output;
    return std::find(fieldNames.begin(), fieldNames.end(), name) != fieldNames.end();
}

vtkSmartPointer<VtkScalarArray> scalarArray(const std::string& name,
                                            const std::vector<Scalar>& data) {
    auto array = vtkSmartPointer<VtkScalarArray>::New();
    array->SetName(name.c_str());
    array->SetNumberOfComponents(1);
    array->SetNumberOfTuples(static_cast<vtkIdType>(data.size()));
    std::copy(data.begin(), data.end(), array->GetPointer(0));
    return array;
}

vtkSmartPointer<VtkScalarArray> vectorArray(const std::string& name,
                                            const std::vector<Vec3>& data) {
    auto array = vtkSmartPointer<VtkScalarArray>::New();
    array->SetName(name.c_str());
    array->SetNumberOfComponents(3);
    array->SetNumberOfTuples(static_cast<vtkIdType>(data.size()));
    Scalar* out = array->GetPointer(0);
    for (std::size_t i = 0; i < data.size(); ++i) {
        out[3 * i + 0] = data[i][0];
        out[3 * i + 1] = data[i][1];
        out[3 * i + 2] = data[i][2];
    }
    return array;
}

// True when 'name' is a finite number written as a whole (strtod reads all of it).
bool parseNumber(const std::string& name, double& value) {
    if (name.empty()) return false;
    const char* begin = name.c_str();
    char* end = nullptr;
    value = std::strtod(begin, &end);
    return end == begin + name.size() && std::isfinite(value);
}

// True when the file ends with "</VTKFile>" (and white space): a cheap check that it is not
// truncated, before VTK reads array sizes from a possibly missing appended-data section.
bool endsWithClosingTag(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    if (!in || size <= 0) return false;
    const std::streamoff tail = std::min<std::streamoff>(size, 256);
    std::string text(static_cast<std::size_t>(tail), '\0');
    in.seekg(size - tail);
    in.read(text.data(), tail);
    if (!in) return false;
    const auto last = text.find_last_not_of(" \t\r\n");
    const std::string tag = "</VTKFile>";
    return last != std::string::npos && last + 1 >= tag.size() &&
           text.compare(last + 1 - tag.size(), tag.size(), tag) == 0;
}

// Writes 'text' to 'file' (complete, or an exception naming it and nothing left).
void writeTextFile(const fs::path& file, const std::string& text) {
    errno = 0;
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    if (out) out << text;
    if (out) out.close();
    if (!out) {
        const int error = errno; // (before the remove sets another)
        std::error_code ec;
        fs::remove(file, ec);
        throw std::runtime_error(describeWriteFailure(file.string(), error));
    }
}

// Renames 'from' to 'to' (replacing a file), or an exception naming both.
void renameFile(const fs::path& from, const fs::path& to) {
    std::error_code ec;
    fs::rename(from, to, ec);
    if (ec) {
        std::error_code ignored;
        fs::remove(from, ignored);
        throw std::runtime_error("cannot rename '" + from.string() + "' to '" + to.string() + "': " + ec.message());
    }
}

} // namespace

// ---------------------------------------------------------------------------------------------
// .vtp files

void writeVtp(const fs::path& file, const ParticleSet& set,
              const std::vector<std::string>& fieldNames, bool restartFields, bool compressed) {
    const std::size_t n = set.size();
    const auto count = static_cast<vtkIdType>(n);

    vtkNew<vtkPolyData> poly;

    vtkNew<vtkPoints> points;
    points->SetDataType(vtkScalarType);
    points->SetNumberOfPoints(count);
    {
        auto* coords = static_cast<Scalar*>(points->GetData()->GetVoidPointer(0));
        const auto& x = set.position();
        for (std::size_t i = 0; i < n; ++i) {
            coords[3 * i + 0] = x[i][0];
            coords[3 * i + 1] = x[i][1];
            coords[3 * i + 2] = x[i][2];
        }
    }
    poly->SetPoints(points);

    // One vertex cell per particle: offsets 0..n, connectivity 0..n-1.
    vtkNew<vtkIdTypeArray> offsets;
    vtkNew<vtkIdTypeArray> connectivity;
    offsets->SetNumberOfTuples(count + 1);
    connectivity->SetNumberOfTuples(count);
    for (vtkIdType i = 0; i < count; ++i) {
        offsets->SetValue(i, i);
        connectivity->SetValue(i, i);
    }
    offsets->SetValue(count, count);
    vtkNew<vtkCellArray> verts;
    verts->SetData(offsets, connectivity);
    poly->SetVerts(verts);

    vtkPointData* pointData = poly->GetPointData();
    {
        vtkNew<vtkTypeUInt32Array> id;
        id->SetName("id");
        id->SetNumberOfComponents(1);
        id->SetNumberOfTuples(count);
        std::copy(set.id().begin(), set.id().end(), id->GetPointer(0));
        pointData->AddArray(id);
    }
    for (const auto& f : set.scalarFields()) {
        if (f->data.size() != n || !selected(f->name, f->options, fieldNames, restartFields)) continue;
        pointData->AddArray(scalarArray(f->name, f->data));
    }
    for (const auto& f : set.vectorFields()) {
        if (f->name == "position" || f->data.size() != n ||
            !selected(f->name, f->options, fieldNames, restartFields))
            continue;
        pointData->AddArray(vectorArray(f->name, f->data));
    }
    {
        vtkNew<VtkScalarArray> mass;
        mass->SetName("particleMass");
        mass->SetNumberOfComponents(1);
        mass->SetNumberOfTuples(1);
        mass->SetValue(0, set.particleMass());
        poly->GetFieldData()->AddArray(mass);
    }

    writePolyData(file, *poly, compressed);
}

void writePolyData(const fs::path& file, vtkPolyData& data, bool compressed) {
    vtkNew<vtkXMLPolyDataWriter> writer;
    vtkNew<ErrorCollector> errors;
    writer->AddObserver(vtkCommand::ErrorEvent, errors);
    writer->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
    writer->SetFileName(file.string().c_str());
    writer->SetInputData(&data);
    writer->SetDataModeToAppended();
    writer->EncodeAppendedDataOff(); // raw binary
    if (compressed) writer->SetCompressorTypeToLZ4();
    else writer->SetCompressorTypeToNone();
    writer->SetHeaderTypeToUInt64(); // arrays above 4 GiB
    const int ok = writer->Write();
    // A system error (VTK keeps errno as its error code: ENOSPC on a full disk, after removing
    // the part it wrote) is named as such; VTK's own text says only that the algorithm failed.
    const unsigned long code = writer->GetErrorCode();
    if (code == vtkErrorCode::OutOfDiskSpaceError)
        throw std::runtime_error(describeWriteFailure(file.string(), ENOSPC));
    if (code > 0 && code < vtkErrorCode::FirstVTKErrorCode)
        throw std::runtime_error(describeWriteFailure(file.string(), int(code)));
    if (!ok || writer->GetErrorCode() != 0 || errors->any())
        throw std::runtime_error("cannot write '" + file.string() + "'" +
                                 (errors->any() ? ": " + errors->message() : std::string()));
}

ParticleSet readVtp(const fs::path& file, const std::string& setName) {
    std::error_code ec;
    if (!fs::is_regular_file(file, ec))
        throw std::runtime_error("cannot read '" + file.string() + "': no such file");

    vtkNew<vtkXMLPolyDataReader> reader;
    vtkNew<ErrorCollector> errors;
    reader->AddObserver(vtkCommand::ErrorEvent, errors);
    reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
    reader->SetReaderErrorObserver(errors);
    reader->SetParserErrorObserver(errors);
    if (!reader->CanReadFile(file.string().c_str()))
        throw std::runtime_error("cannot read '" + file.string() +
                                 "': not a VTK XML PolyData file");
    if (!endsWithClosingTag(file))
        throw std::runtime_error("cannot read '" + file.string() +
                                 "': truncated (no closing </VTKFile>)");
    reader->SetFileName(file.string().c_str());
    try {
        reader->Update();
    } catch (const std::exception& e) { // e.g. bad_alloc for a garbage array size
        throw std::runtime_error("cannot read '" + file.string() + "': " + e.what());
    }
    vtkPolyData* poly = reader->GetOutput();
    if (errors->any() || reader->GetErrorCode() != 0 || !poly)
        throw std::runtime_error("cannot read '" + file.string() + "'" +
                                 (errors->any() ? ": " + errors->message() : std::string()));

    ParticleSet set(setName);
    const vtkIdType count = poly->GetNumberOfPoints();
    const auto n = static_cast<std::size_t>(count);
    set.resize(n);

    if (vtkPoints* points = poly->GetPoints()) {
        auto& x = set.position();
        double p[3];
        for (vtkIdType i = 0; i < count; ++i) {
            points->GetPoint(i, p);
            x[static_cast<std::size_t>(i)] =
                Vec3(static_cast<Scalar>(p[0]), static_cast<Scalar>(p[1]),
                     static_cast<Scalar>(p[2]));
        }
    }

    vtkPointData* pointData = poly->GetPointData();
    for (int a = 0; a < pointData->GetNumberOfArrays(); ++a) {
        vtkDataArray* array = pointData->GetArray(a); // null for non-numeric arrays
        if (!array || !array->GetName() || array->GetNumberOfTuples() != count) continue;
        const std::string name = array->GetName();
        const int components = array->GetNumberOfComponents();
        if (name == "id" && components == 1) {
            auto& id = set.id();
            for (vtkIdType i = 0; i < count; ++i)
                id[static_cast<std::size_t>(i)] = static_cast<Index>(array->GetComponent(i, 0));
        } else if (components == 1) {
            auto& data = set.addScalar(name);
            for (vtkIdType i = 0; i < count; ++i)
                data[static_cast<std::size_t>(i)] = static_cast<Scalar>(array->GetComponent(i, 0));
        } else if (components == 3 && name != "position") {
            auto& data = set.addVector(name);
            for (vtkIdType i = 0; i < count; ++i)
                data[static_cast<std::size_t>(i)] =
                    Vec3(static_cast<Scalar>(array->GetComponent(i, 0)),
                         static_cast<Scalar>(array->GetComponent(i, 1)),
                         static_cast<Scalar>(array->GetComponent(i, 2)));
        }
    }

    if (vtkFieldData* fieldData = poly->GetFieldData())
        if (vtkDataArray* mass = fieldData->GetArray("particleMass"))
            if (mass->GetNumberOfTuples() >= 1 && mass->GetNumberOfComponents() == 1)
                set.setParticleMass(static_cast<Scalar>(mass->GetComponent(0, 0)));
    return set;
}

// ---------------------------------------------------------------------------------------------
// CaseWriter

CaseWriter::CaseWriter(fs::path caseDir, int timePrecision, double earliestTime)
    : caseDir_(std::move(caseDir)), precision_(timePrecision), earliestTime_(earliestTime) {}

std::string CaseWriter::timeName(double time, int precision) {
    if (time == 0) time = 0; // no "-0"
    std::ostringstream s;
    s << std::setprecision(precision) << time;
    return s.str();
}

bool CaseWriter::isTimeName(const std::string& name, double& value) const {
    if (!parseNumber(name, value) || value < earliestTime_) return false;
    for (int digits = 1; digits <= 17; ++digits)
        if (timeName(value, digits) == name) return true;
    return false;
}

fs::path CaseWriter::collectionFile() const {
    std::error_code ec;
    fs::path dir = fs::weakly_canonical(fs::absolute(caseDir_), ec);
    if (ec) dir = fs::absolute(caseDir_).lexically_normal();
    if (dir.filename().empty()) dir = dir.parent_path(); // trailing slash
    std::string name = dir.filename().string();
    if (name.empty() || name == "." || name == "..") name = "case";
    return caseDir_ / (name + ".pvd");
}

std::vector<std::pair<double, std::string>> CaseWriter::existingTimes() const {
    std::vector<std::pair<double, std::string>> times;
    std::error_code ec;
    if (!fs::is_directory(caseDir_, ec)) return times;
    for (fs::directory_iterator it(caseDir_, ec), end; !ec && it != end; it.increment(ec)) {
        std::error_code entryEc;
        if (!it->is_directory(entryEc)) continue;
        const std::string name = it->path().filename().string();
        double value = 0;
        if (!isTimeName(name, value)) continue; // also skips hidden ".<time>.tmp"
        if (!fs::is_regular_file(it->path() / "fluid.vtp", entryEc)) continue;
        times.emplace_back(value, name);
    }
    std::sort(times.begin(), times.end());
    return times;
}

namespace {
// The systems but the fluid a time directory holds: its .vtp files but fluid.vtp, sorted.
std::vector<std::string> otherFilesIn(const fs::path& dir) {
    std::vector<std::string> walls;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const fs::path& f = it->path();
        if (f.extension() == ".vtp" && f.stem() != "fluid") walls.push_back(f.stem().string());
    }
    std::sort(walls.begin(), walls.end());
    return walls;
}

// Test hook: SPINDRIFT_FAULT_INJECTION=<what>:N kills the process at the N-th time it passes
// the point 'what' names (killDuringWrite, killAfterRename).
void maybeKill(const char* what) {
    const char* v = std::getenv("SPINDRIFT_FAULT_INJECTION");
    if (!v) return;
    const std::string prefix = std::string(what) + ":";
    if (std::string(v).rfind(prefix, 0) != 0) return;
    static std::map<std::string, int> passes;
    if (++passes[what] == std::atoi(v + prefix.size())) ::raise(SIGKILL);
}

// Removes what was moved to 'old' to make way for a new time; what cannot be removed (a
// directory of another user, mode 000) stays there, named in a warning.
void removeReplaced(const fs::path& old, const std::string& what) {
    std::error_code ec;
    fs::remove_all(old, ec);
    if (ec)
        log::warning(what + ": the earlier contents could not be removed (" + ec.message() + "); they are kept in " +
                     old.string() + ": remove it by hand");
}

// Whether anything (a directory, a file, a link, even a dangling one) has this path.
bool anythingAt(const fs::path& p) {
    std::error_code ec;
    return fs::exists(fs::symlink_status(p, ec));
}
} // namespace

CaseWriter::RunStart CaseWriter::beginRun(double from, const std::string& continued) {
    RunStart start;
    double continuedValue = 0;
    const bool continuing = !continued.empty() && parseNumber(continued, continuedValue);
    const std::string fromName = timeName(from, precision_);
    // the entries named as later times, and the listed ones
    std::vector<std::pair<double, std::string>> later;
    std::error_code ec;
    for (fs::directory_iterator it(caseDir_, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        double value = 0;
        if (!isTimeName(name, value)) continue;
        const bool isLater =
            continuing ? value > continuedValue && name != continued : value >= from || name == fromName;
        if (isLater) later.emplace_back(value, name);
    }
    std::sort(later.begin(), later.end());
    times_.clear();
    for (const auto& [value, name] : existingTimes()) {
        const std::string& timeName = name; // clang 14 cannot capture a structured binding
        const bool moved =
            std::any_of(later.begin(), later.end(), [&](const auto& l) { return l.second == timeName; });
        if (moved) continue;
        if (continuing) times_.push_back({value, name, otherFilesIn(caseDir_ / name)});
        else start.notListed.push_back(name);
    }
    written_.clear();
    writeCollection(); // first: it never lists a time that is being moved
    if (later.empty()) return start;
    const fs::path aside = caseDir_ / "previousRun";
    if (anythingAt(aside)) {
        fs::remove_all(aside, ec);
        if (ec)
            throw std::runtime_error("cannot remove '" + aside.string() + "' (" + ec.message() +
                                     ") to move the times of an earlier run there; remove it by hand");
        start.replacedPreviousRun = true;
    }
    fs::create_directory(aside, ec);
    if (ec) throw std::runtime_error("cannot create '" + aside.string() + "': " + ec.message());
    for (const auto& [value, name] : later) {
        fs::rename(caseDir_ / name, aside / name, ec);
        if (ec)
            throw std::runtime_error("cannot move '" + (caseDir_ / name).string() + "' (an earlier run's time " + name +
                                     ") to '" + aside.string() + "': " + ec.message() +
                                     "; remove it (or make it writable): this run would mix it into its results");
        start.movedAside.push_back(name);
    }
    return start;
}

void CaseWriter::write(double time, const ParticleSet& fluid, const std::vector<SystemFile>& others,
                       const std::vector<std::string>& fieldNames,
                       const std::vector<std::pair<std::string, std::string>>& extraFiles,
                       const std::vector<Block>& blocks) {
    const std::string name = timeName(time, precision_);
    // two times of one name: the second would replace the first's results (the schedule is
    // checked before the run; this catches what it cannot foresee, e.g. writeControl timeStep
    // with an adjusted Δt)
    if (const auto same = written_.find(name); same != written_.end() &&
                                                   std::abs(same->second - time) > 1e-12 * std::max(1.0, std::abs(time))) {
        std::ostringstream s;
        s << std::setprecision(17) << "times " << same->second << " and " << time << " both have the name '" << name
          << "' at timePrecision " << precision_ << ": not overwriting the first; raise timePrecision";
        throw std::runtime_error(s.str());
    }
    const fs::path finalDir = caseDir_ / name;
    const fs::path tmpDir = caseDir_ / ("." + name + ".tmp");
    const fs::path old = caseDir_ / ("." + name + ".old");
    fs::path collectionTmp = collectionFile();
    collectionTmp += ".tmp";

    std::error_code ec;
    fs::create_directories(caseDir_, ec);
    if (ec)
        throw std::runtime_error("cannot create the case directory '" + caseDir_.string() +
                                 "': " + ec.message());
    fs::remove_all(tmpDir, ec); // stale, from an interrupted run
    if (!fs::create_directory(tmpDir, ec) || ec)
        throw std::runtime_error(ec == std::errc::no_space_on_device
                                     ? describeWriteFailure(tmpDir.string(), ENOSPC) + ": time " + name + " not written"
                                     : "cannot create '" + tmpDir.string() + "': " +
                                           (ec ? ec.message() : std::string("it exists")));

    // the list of times with this one (replacing an entry of the same name)
    std::vector<TimeEntry> times = times_;
    TimeEntry entry{time, name, {}};
    parseNumber(name, entry.value);
    bool replacing = false;
    try {
        writeVtp(tmpDir / "fluid.vtp", fluid, fieldNames, true);
        for (const SystemFile& o : others) {
            writeVtp(tmpDir / (o.set->name() + ".vtp"), *o.set, fieldNames, o.restart, !o.restart);
            entry.others.push_back(o.set->name());
        }
        for (const Block& b : blocks) {
            if (b.name == "fluid" || std::count(entry.others.begin(), entry.others.end(), b.name))
                throw std::runtime_error("two blocks of the time are named '" + b.name + "'");
            b.write(tmpDir / (b.name + ".vtp"));
            entry.others.push_back(b.name);
        }
        std::sort(entry.others.begin(), entry.others.end());
        for (const auto& [relative, content] : extraFiles) {
            const fs::path file = tmpDir / relative;
            fs::create_directories(file.parent_path());
            writeTextFile(file, content);
        }
        std::erase_if(times, [&](const TimeEntry& e) { return e.name == name; });
        times.insert(std::upper_bound(times.begin(), times.end(), entry,
                                      [](const TimeEntry& a, const TimeEntry& b) {
                                          return a.value < b.value || (a.value == b.value && a.name < b.name);
                                      }),
                     entry);
        // the .pvd with this time, ready before the directory's rename: renamed right after it
        writeTextFile(collectionTmp, collectionText(times));
        maybeKill("killDuringWrite");
        // whatever has the name (an earlier write of this time, a dangling link) is set aside
        // until the new directory is in place
        if (anythingAt(finalDir)) {
            if (anythingAt(old)) {
                fs::remove_all(old, ec);
                if (ec)
                    throw std::runtime_error("cannot remove '" + old.string() + "' (" + ec.message() +
                                             ", left by an earlier write of this time); remove it by hand");
            }
            fs::rename(finalDir, old);
            replacing = true;
        }
        fs::rename(tmpDir, finalDir);
    } catch (const std::exception& e) {
        // the part written is removed (on a full disk, the space it took is given back); the
        // times written before are untouched
        fs::remove_all(tmpDir, ec);
        fs::remove(collectionTmp, ec);
        if (replacing && !anythingAt(finalDir)) fs::rename(old, finalDir, ec); // put back
        const auto* fsError = dynamic_cast<const fs::filesystem_error*>(&e);
        if (fsError && fsError->code() == std::errc::no_space_on_device)
            throw std::runtime_error(describeWriteFailure(fsError->path1().string(), ENOSPC) + ": time " + name +
                                     " not written; the times written before it are complete");
        if (fsError)
            throw std::runtime_error("cannot write time directory '" + finalDir.string() + "': " + e.what() +
                                     "; the times written before it are complete");
        throw std::runtime_error(std::string(e.what()) + ": time " + name +
                                 " not written; the times written before it are complete");
    }
    maybeKill("killAfterRename");
    renameFile(collectionTmp, collectionFile());
    times_ = std::move(times);
    written_[name] = time;
    if (replacing) removeReplaced(old, "time " + name);
}

std::vector<std::string> CaseWriter::removeTimesWrittenAfter(double time) {
    std::vector<std::string> removed;
    for (const auto& [name, value] : written_)
        if (value > time && timeName(time, precision_) != name) removed.push_back(name);
    if (removed.empty()) return removed;
    std::erase_if(times_, [&](const TimeEntry& e) {
        return std::find(removed.begin(), removed.end(), e.name) != removed.end();
    });
    writeCollection();
    for (const auto& name : removed) {
        written_.erase(name);
        const fs::path hidden = caseDir_ / ("." + name + ".removed");
        std::error_code ec;
        fs::remove_all(hidden, ec);
        fs::rename(caseDir_ / name, hidden, ec);
        if (ec)
            log::warning("time " + name + " (abandoned) could not be removed: " + ec.message());
        else
            removeReplaced(hidden, "time " + name + " (abandoned)");
    }
    return removed;
}

std::string CaseWriter::collectionText(const std::vector<TimeEntry>& times) const {
    std::ostringstream s;
    s << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <Collection>\n";
    // every other system of the times listed gets a part of its own, in name order (the same
    // part number at every time); each time shows the systems its directory holds
    std::map<std::string, int> part;
    for (const auto& e : times)
        for (const auto& w : e.others) part.emplace(w, 0);
    int next = 1;
    for (auto& [wall, number] : part) number = next++;
    for (const auto& e : times) {
        s << "    <DataSet timestep=\"" << e.name << "\" group=\"\" part=\"0\" file=\""
          << e.name << "/fluid.vtp\" name=\"fluid\"/>\n";
        for (const auto& w : e.others)
            s << "    <DataSet timestep=\"" << e.name << "\" group=\"\" part=\"" << part[w] << "\" file=\""
              << e.name << "/" << w << ".vtp\" name=\"" << w << "\"/>\n";
    }
    s << "  </Collection>\n"
      << "</VTKFile>\n";
    return s.str();
}

void CaseWriter::writeCollection() const {
    std::error_code ec;
    fs::create_directories(caseDir_, ec);
    fs::path tmp = collectionFile();
    tmp += ".tmp";
    writeTextFile(tmp, collectionText(times_));
    renameFile(tmp, collectionFile());
}

} // namespace spindrift
