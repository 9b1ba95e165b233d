// Spindrift — `spindrift -postProcess [-func NAME] [-time RANGE]`, as OpenFOAM's `postProcess
// -func`: runs the case's function objects (controlDict `functions`), or the one named, over the
// times it has written, without solving — probes added after a run, a waterLevel or fieldStats
// read off old results. At each selected time the state written there is loaded
// (Simulation::loadWrittenTime: the fluid's fields, the exact time and step, the moving walls
// placed at that time) and every object samples it, whatever its writeControl (a written time is
// all there is to sample). Output: postProcessing/<name>/<first selected time>/, as a run that
// starts at that time and writes at the others writes it: the rows a run wrote with `writeControl
// writeTime` are reproduced (tests/cases/postProcess.sh). Nothing else of the case is changed.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace spindrift {

class Simulation;

struct PostProcessRequest {
    std::string function; // -func: one function object of controlDict's `functions` (empty: all)
    std::string times;    // -time: a selection for selectTimes() (empty: every written time)
};

// Runs the request on the case of 'sim' (constructed, not run); logs a line per time and a
// summary. Throws InputError (an unknown -func, naming controlDict's `functions`) or
// std::runtime_error (a -time that selects nothing, naming the written times).
void postProcess(Simulation& sim, const PostProcessRequest& request);

// The times of 'written' (time, name; sorted) that 'selection' selects: a comma-separated list of
// times and ranges "a:b" (inclusive, either end may be left out: ":0.2", "0.4:"), OpenFOAM's
// -time syntax; an empty selection selects all. A time matches a value within 1e-9 of it
// (relative) or by its name. Throws std::runtime_error on a selection that is not one.
std::vector<std::pair<double, std::string>> selectTimes(const std::vector<std::pair<double, std::string>>& written,
                                                        const std::string& selection);

} // namespace spindrift
