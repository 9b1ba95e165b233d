// Spindrift — function objects (plugins/functionObjects), OpenFOAM-style: configured in
// controlDict `functions { name { type probes; ... } }`, executed after every step (or every
// `executeInterval` steps), writing tabular output to
// postProcessing/<name>/<startTime>/<name>.dat through PostProcessingFile, or a block of their
// own in every written time directory (<block>.vtp, listed in the .pvd: freeSurface's mesh).
#pragma once

#include "ModelContext.hpp"

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace spindrift {

class FunctionObject {
public:
    virtual ~FunctionObject() = default;
    // Called once after set-up, before start(): asks the core for what it needs computed beyond
    // the run itself, e.g. the forces on walls and bodies (Scene::reactions.want).
    virtual void require(Scene&) {}
    // Called once after set-up, with the start time (the output folder's name).
    virtual void start(const Scene&, double startTime) { (void)startTime; }
    // Called after each step; 'writeTime' is true when the solver writes a time directory.
    virtual void execute(const Scene& system, bool writeTime) = 0;
    virtual void end(const Scene&) {}
    // A block of its own in every written time: its name (the file <name>.vtp beside the systems'
    // files, a part of the .pvd), empty for none. Asked once after set-up.
    virtual std::string blockName() const { return {}; }
    // Writes the block of the scene's state to 'file' (VTK XML PolyData: writePolyData) while the
    // solver writes a time directory, before execute() of that step.
    virtual void writeBlock(const Scene&, const std::filesystem::path& file) { (void)file; }
};

// A column of a postProcessing table: its name and its unit as the header shows it ("Pa", "m/s",
// "%", "-" for a count or a ratio).
struct PostProcessingColumn {
    std::string name, unit;
};

// postProcessing/<name>/<startTimeName>/<fileName>: two '#'-header lines, the columns' names and
// their units (the first column is Time, in s), then one row per call:
//     # Time  nParticles  rhoErrMax ...
//     # [s]   [-]         [%] ...
// Rows are flushed so a crashed run keeps them; restarting appends to a new folder named after
// the restart time, as OpenFOAM does.
class PostProcessingFile {
public:
    PostProcessingFile() = default;
    PostProcessingFile(const std::filesystem::path& caseDir, const std::string& name, double startTime,
                       const std::vector<PostProcessingColumn>& columns, const std::string& fileName = "");
    void writeRow(double time, const std::vector<double>& values);
    const std::filesystem::path& path() const { return path_; }
    bool isOpen() const { return out_.is_open(); }

private:
    std::filesystem::path path_;
    std::ofstream out_;
};

} // namespace spindrift
