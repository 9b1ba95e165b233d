// Spindrift — output of a case: one directory per written time holding a .vtp file per
// particle system (fluid.vtp, and <wall>.vtp for each wall system written that time), plus
// <caseName>.pvd at the case root listing every complete time, one block (part) per system.
//
// Files are VTK XML PolyData, binary appended, written with the VTK library; points are the
// particle positions (one vertex cell per particle), point-data arrays are the set's fields.
// A time directory is written under a temporary name (".<time>.tmp") and renamed when
// complete; the .pvd is written to a temporary file and renamed. So a crash never leaves a
// half-written time directory visible, and the .pvd lists only complete ones.
// Fault injection for tests: with SPINDRIFT_FAULT_INJECTION=killDuringWrite:N in the
// environment, the process kills itself (SIGKILL) in the middle of its N-th write.
#pragma once

#include "ParticleSet.hpp"

#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace spindrift {

class CaseWriter {
public:
    // caseDir: the case root; the collection file is <caseDir>/<caseName>.pvd with
    // caseName = the directory's name.
    explicit CaseWriter(std::filesystem::path caseDir, int timePrecision = 6);

    // OpenFOAM-style time name: general format with 'precision' significant digits
    // (0 -> "0", 0.05 -> "0.05", 1e-05 -> "1e-05", 1.25 -> "1.25").
    static std::string timeName(double time, int precision = 6);

    // Writes <caseDir>/<timeName(time)>/fluid.vtp and <name>.vtp for each of 'walls' (named by
    // their sets), then rewrites the .pvd. A wall written once (a fixed wall) is referenced from
    // every later time: the .pvd points each wall's block to the newest <name>.vtp at or before
    // each time. 'fieldNames': arrays to write besides 'id' (empty = every field flagged
    // output); fields flagged restart are always written, scratch and undefined fields never.
    // 'extraFiles': further files written into the time directory before it is renamed
    // (relative path, content), e.g. uniform/time with the exact time and step for restarts.
    void write(double time, const ParticleSet& fluid, const std::vector<const ParticleSet*>& walls,
               const std::vector<std::string>& fieldNames = {},
               const std::vector<std::pair<std::string, std::string>>& extraFiles = {});

    // Complete time directories present in the case (numeric name holding fluid.vtp),
    // sorted by time.
    std::vector<std::pair<double, std::string>> existingTimes() const;

    // Rebuilds the .pvd from the complete time directories present (used at start-up).
    void rebuildCollection();

    // Removes the times this writer wrote after 'time' (a blow-up's roll-back: they hold the
    // abandoned states, and 'startFrom latestTime' would restart from them): the .pvd is
    // rewritten without them first, then each directory is renamed to a hidden name and
    // removed, so no reader sees a half-removed time. Returns their names.
    std::vector<std::string> removeTimesWrittenAfter(double time);

    const std::filesystem::path& caseDir() const { return caseDir_; }
    std::filesystem::path collectionFile() const;

private:
    struct TimeEntry {
        double value;                   // the time name's numeric value
        std::string name;               // directory name
        std::vector<std::string> walls; // the wall systems it holds (<name>.vtp), sorted
    };
    void scan();                  // fills times_ from the case directory
    void writeCollection() const; // writes the .pvd from times_

    std::filesystem::path caseDir_;
    int precision_;
    std::vector<TimeEntry> times_; // complete times, sorted (scanned once, then kept up to date)
    std::map<std::string, double> written_; // name -> time, of the times this writer wrote
    bool scanned_ = false;
};

// Writes one particle set as a .vtp file (binary appended) — used by CaseWriter.
void writeVtp(const std::filesystem::path& file, const ParticleSet& set,
              const std::vector<std::string>& fieldNames = {});

// Reads a .vtp written by writeVtp back into a ParticleSet: positions, id, and every
// point-data array as a scalar (1 component) or vector (3 components) field.
ParticleSet readVtp(const std::filesystem::path& file, const std::string& setName = "fluid");

} // namespace spindrift
