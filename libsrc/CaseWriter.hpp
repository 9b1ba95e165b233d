// Spindrift — output of a case: one directory per written time holding a .vtp file per
// particle system (fluid.vtp and <system>.vtp for every wall, body and passive system: each time
// directory is whole by itself), plus <caseName>.pvd at the case root listing the times of this run, one block
// (part) per system, and one per block a function object adds (e.g. freeSurface's surface.vtp).
//
// Files are VTK XML PolyData, binary appended, written with the VTK library; points are the
// particle positions (one vertex cell per particle), point-data arrays are the set's fields.
// A wall's file is LZ4-compressed: written at every time (its own pressure changes), the
// positions, cells and zero velocities of a fixed wall compress well (damBreak3D's tank at
// t = 0.02: 6.6 MB raw, 1.7 MB in as long to write; zlib: 0.7 MB in 35 times as long); the
// fluid's is raw (the restart's data, written as fast as it can be).
// A time directory is written under a temporary name (".<time>.tmp") and renamed when
// complete, so a crash never leaves a half-written time directory visible. The .pvd is never
// ahead of the directories (it lists no time that is not complete): its new text is written to
// "<case>.pvd.tmp" before the time directory's rename and renamed right after it. It can be
// behind by the newest time between those two renames — two names cannot change in one atomic
// step — and stays so if the process is killed in between (kill -9); the next run of the case
// lists that time again (beginRun).
// Time names are canonical: what timeName() gives at some precision ("0.025", "1e-05"); a
// directory named " 0.025", "0x1p-6" or "0.0250", or before the earliest time (negative, for a
// case that starts at 0) is not a time.
// Fault injection for tests: with SPINDRIFT_FAULT_INJECTION=killDuringWrite:N in the
// environment, the process kills itself (SIGKILL) in the middle of its N-th write (its files
// complete, before the rename); with killAfterRename:N, between the rename of its N-th time
// directory and that of the .pvd.
#pragma once

#include "ParticleSet.hpp"

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

class vtkPolyData;

namespace spindrift {

class CaseWriter {
public:
    // caseDir: the case root; the collection file is <caseDir>/<caseName>.pvd with
    // caseName = the directory's name. earliestTime: a name of a time before it is not one of
    // the case's times (a run's startTime when that is negative; else 0).
    explicit CaseWriter(std::filesystem::path caseDir, int timePrecision = 6, double earliestTime = 0);

    // OpenFOAM-style time name: general format with 'precision' significant digits
    // (0 -> "0", 0.05 -> "0.05", 1e-05 -> "1e-05", 1.25 -> "1.25").
    static std::string timeName(double time, int precision = 6);
    // Whether 'name' names a time: canonical (timeName of its value at some precision from 1 to
    // 17) and not before the earliest time; 'value' gets its value.
    bool isTimeName(const std::string& name, double& value) const;

    // What beginRun did.
    struct RunStart {
        std::vector<std::string> movedAside; // to previousRun/
        bool replacedPreviousRun = false;    // an older previousRun/ was removed first
        std::vector<std::string> notListed;  // times before a fresh run's start, kept on disk
    };
    // Takes the case's times for a run: a fresh run starting at 'from' (continued empty) owns
    // every time from 'from' on; a restart continues the time named 'continued' and those
    // before it. Every entry named as a later time (a fresh run: 'from' and later) — an earlier
    // run's results, a newer time a restart could not use, a dangling link — is moved into
    // <case>/previousRun/ (an older previousRun/ removed first), after the .pvd is rewritten to
    // list the continued times only (none for a fresh run): so neither ParaView nor a later
    // 'startFrom latestTime' mixes them in. Throws std::runtime_error naming an entry that
    // cannot be moved (the run would mix it in).
    RunStart beginRun(double from, const std::string& continued = "");

    // A system written besides the fluid: restart, its restart fields are always written (a
    // passive system's particles continue on a restart), raw; else only those selected,
    // compressed (walls and bodies are sampled anew on a restart).
    struct SystemFile {
        SystemFile(const ParticleSet* system, bool withRestartFields = false) // NOLINT: a wall converts
            : set(system), restart(withRestartFields) {}
        const ParticleSet* set;
        bool restart;
    };
    // A block of a written time that is not a particle system (a function object's, e.g. a
    // surface mesh): 'write' writes it, as VTK XML PolyData, to the file it is given,
    // <time>/<name>.vtp; the .pvd lists it beside the systems.
    struct Block {
        std::string name;
        std::function<void(const std::filesystem::path& file)> write;
    };
    // Writes <caseDir>/<timeName(time)>/fluid.vtp and <name>.vtp for each of 'others' (named by
    // their sets; every other system of the run, so that each time directory is whole) and of
    // 'blocks', then the .pvd. 'fieldNames': arrays to write besides 'id' (empty = every field flagged
    // output); the fluid's fields flagged restart are always written, the others' as
    // SystemFile says; scratch and undefined fields never.
    // 'extraFiles': further files written into the time directory before it is renamed
    // (relative path, content), e.g. uniform/time with the exact time and step for restarts.
    // Whatever had the time's name before (an earlier write of it, a dangling link) is replaced.
    void write(double time, const ParticleSet& fluid, const std::vector<SystemFile>& others,
               const std::vector<std::string>& fieldNames = {},
               const std::vector<std::pair<std::string, std::string>>& extraFiles = {},
               const std::vector<Block>& blocks = {});

    // Complete time directories present in the case (a time's name, holding fluid.vtp),
    // sorted by time.
    std::vector<std::pair<double, std::string>> existingTimes() const;

    // Removes the times this writer wrote after 'time' (a blow-up's roll-back: they hold the
    // abandoned states, and 'startFrom latestTime' would restart from them): the .pvd is
    // rewritten without them first, then each directory is renamed to a hidden name and
    // removed, so no reader sees a half-removed time. Returns their names.
    std::vector<std::string> removeTimesWrittenAfter(double time);

    // How many times this writer wrote that are still there (a time written again counts once).
    std::size_t timesWritten() const { return written_.size(); }

    const std::filesystem::path& caseDir() const { return caseDir_; }
    std::filesystem::path collectionFile() const;

private:
    struct TimeEntry {
        double value;                   // the time name's numeric value
        std::string name;               // directory name
        std::vector<std::string> others; // the systems but the fluid it holds (<name>.vtp), sorted
    };
    std::string collectionText(const std::vector<TimeEntry>& times) const;
    void writeCollection() const; // writes the .pvd from times_

    std::filesystem::path caseDir_;
    int precision_;
    double earliestTime_;
    std::vector<TimeEntry> times_; // the times the .pvd lists, sorted
    std::map<std::string, double> written_; // name -> time, of the times this writer wrote
};

// Writes one particle set as a .vtp file (binary appended) — used by CaseWriter. Writes the
// fields 'fieldNames' selects (empty: those flagged output), and those flagged restart when
// 'restartFields'; 'compressed': the arrays LZ4-compressed (VTK's own compression, read by
// ParaView and readVtp).
void writeVtp(const std::filesystem::path& file, const ParticleSet& set,
              const std::vector<std::string>& fieldNames = {}, bool restartFields = true, bool compressed = false);

// Writes 'data' as a .vtp file (binary appended, LZ4-compressed when 'compressed'); a failure
// (a full disk, VTK's own errors) is a std::runtime_error naming the file. writeVtp's writer, for
// the blocks of function objects too.
void writePolyData(const std::filesystem::path& file, vtkPolyData& data, bool compressed = false);

// Reads a .vtp written by writeVtp back into a ParticleSet: positions, id, and every
// point-data array as a scalar (1 component) or vector (3 components) field.
ParticleSet readVtp(const std::filesystem::path& file, const std::string& setName = "fluid");

} // namespace spindrift
