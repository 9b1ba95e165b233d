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
// what a run leaves behind (time directories, .<time>.tmp, postProcessing/, log.*, *.pvd,
// plots, hidden files), as OpenFOAM's cloneCase. Tests, the bench utilities and ./Allrun copy
// tutorials with it, so they never read another run's results.
void copyCaseInput(const std::filesystem::path& source, const std::filesystem::path& target);
// True for a name a run writes results under: a number (a time directory).
bool isTimeName(const std::string& name);

} // namespace spindrift
