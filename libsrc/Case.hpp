// Spindrift — a case directory: its dictionaries, read once at start-up.
//
//   system/controlDict  system/sphSchemes  system/sphSolution (optional)
//   constant/fluidProperties  constant/geometry
#pragma once

#include "Dictionary.hpp"
#include "Scene.hpp"

#include <filesystem>

namespace spindrift {

struct Case {
    std::filesystem::path dir;
    std::string name; // the directory's name, e.g. "damBreak2D"
    Dictionary controlDict, sphSchemes, sphSolution, fluidProperties, geometry;

    // Reads every dictionary; a missing case directory or file is an InputError naming it.
    static Case read(const std::filesystem::path& dir);
    std::filesystem::path file(const std::string& relative) const { return dir / relative; }
};

// constant/fluidProperties:
//   dimension 2;  rho0 1000;  viscosity 1e-6;  gravity (0 -9.81 0);
//   particleSpacing 0.002;  supportRadius 2.6;  // support h in units of particleSpacing
PhysicalParameters readPhysicalParameters(const Dictionary& fluidProperties);

// Copies a case's input to 'target' (created; it must not exist or be empty): everything but
// what a run leaves behind (time directories, .<time>.tmp, postProcessing/, previousRun/, log.*,
// *.pvd, plots, hidden files), as OpenFOAM's cloneCase. Tests, the bench utilities and ./Allrun
// copy tutorials with it, so they never read another run's results.
void copyCaseInput(const std::filesystem::path& source, const std::filesystem::path& target);
// The case's lock: <case>/.spindrift.lock holding "pid host", so that two solvers never write
// into one case (the second would overwrite or delete the first's time directories). Taken
// with an atomic link() of a complete temporary file, so the lock file is never seen empty.
// A lock whose pid is dead on this host is stale (a killed run): taken over with a warning.
// A live one (or one from another host, which cannot be checked) is an InputError naming the
// pid and host. A second lock by the same process (tests running two Simulations) shares it.
// Removed by the destructor, or by releaseInSignalHandler() when a signal ends the process
// (SIGINT during set-up); a run killed by SIGKILL leaves a stale lock, taken over next time.
class CaseLock {
public:
    explicit CaseLock(const std::filesystem::path& caseDir);
    ~CaseLock();
    // Removes this process's lock file (and the temporary one it is made from), if any: for a
    // signal handler that ends the process (async-signal-safe: open, read, close, unlink).
    static void releaseInSignalHandler() noexcept;
    CaseLock(const CaseLock&) = delete;
    CaseLock& operator=(const CaseLock&) = delete;
    static std::filesystem::path file(const std::filesystem::path& caseDir) { return caseDir / ".spindrift.lock"; }

private:
    std::filesystem::path file_;
    bool owner_ = false; // created the file (a nested lock of the same process does not remove it)
};

// True for a name a run writes results under: a number (a time directory).
bool isTimeName(const std::string& name);

} // namespace spindrift
