// libFuzzer target: system/sphSchemes and system/sphSolution semantics — the models a case names,
// their parameters and how they combine — run end to end on a small fixed case (a 2D dam break
// of 20 fluid particles in a three-layer tank, with a moving paddle: every boundary model meets
// a moving wall). The input is sphSchemes, optionally followed by a NUL byte and sphSolution. The
// plugins are loaded at run time from the instrumented build (tests/fuzz/CMakeLists.txt), so the
// fuzzer sees their coverage too.
//
// Any input must end in one of: an InputError (file:line:col and keyword), the blow-up error of
// the time loop (a state it refuses to go on from, the last good one named), or a run of a few
// steps whose particles are all finite — never a crash, a leak, a hang, a sanitizer report or
// another exception.
#include "Error.hpp"
#include "FuzzSupport.hpp"
#include "Simulation.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

using namespace spindrift;
using fuzz::check;
namespace fs = std::filesystem;

namespace {

const char* const controlDict = R"(FoamFile { class dictionary; object controlDict; }
application     spindrift;
startFrom       startTime;
startTime       0;
stopAt          endTime;
endTime         0.0003;
deltaT          0.0001;
adjustTimeStep  no;
writeControl    runTime;
writeInterval   1;
runTimeModifiable no;
)";

const char* const fluidProperties = R"(FoamFile { class dictionary; object fluidProperties; }
dimension       2;
rho0            1000;
viscosity       1e-6;
gravity         (0 -9.81 0);
particleSpacing 0.02;
supportRadius   3;
)";

const char* const geometry = R"(FoamFile { class dictionary; object geometry; }
fluid { water { type box; min (0.08 0 0); max (0.16 0.1 0); initialPressure hydrostatic; } }
walls
{
    tank { type container; min (0 0 0); max (0.24 0.14 0); layers 3; open (yMax); }
    paddle
    {
        type box; min (0 0 0); max (0.06 0.12 0);
        motion { type oscillating; direction (1 0 0); amplitude 0.002; period 0.01; }
    }
}
)";

void write(const fs::path& file, const std::string& text) {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out << text;
}

// A case directory of its own in /dev/shm (or $TMPDIR) with the fixed files; emptied of
// results before each input, removed when the fuzzer exits.
struct CaseDirectory {
    fs::path path;
    ~CaseDirectory() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

const fs::path& caseDirectory() {
    static const CaseDirectory dir{[] {
        const fs::path shm = fs::is_directory("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
        const fs::path d = shm / ("spindriftFuzzSchemes." + std::to_string(::getpid()));
        fs::create_directories(d / "system");
        fs::create_directories(d / "constant");
        write(d / "system" / "controlDict", controlDict);
        write(d / "constant" / "fluidProperties", fluidProperties);
        write(d / "constant" / "geometry", geometry);
        return d;
    }()};
    return dir.path;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fuzz::quietLog();
    const fs::path& dir = caseDirectory();
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.path().filename() != "system" && entry.path().filename() != "constant") fs::remove_all(entry.path());

    const std::string text(reinterpret_cast<const char*>(data), size);
    const std::size_t split = text.find('\0');
    write(dir / "system" / "sphSchemes", text.substr(0, split));
    if (split == std::string::npos) fs::remove(dir / "system" / "sphSolution");
    else write(dir / "system" / "sphSolution", text.substr(split + 1));

    try {
        Simulation simulation(dir);
        const RunSummary summary = simulation.run();
        check(summary.steps >= 1);
        for (const ParticleSystem* fluid : simulation.scene().ofRole(SystemRole::fluid)) {
            for (const auto& x : fluid->particles.position()) check(x.allFinite());
            for (const auto& v : fluid->particles.velocity()) check(v.allFinite());
        }
    } catch (const InputError&) {
    } catch (const BlowUpError&) {
    }
    return 0;
}
