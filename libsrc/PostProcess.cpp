#include "PostProcess.hpp"

#include "Error.hpp"
#include "FunctionObject.hpp"
#include "Log.hpp"
#include "Simulation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>
#include <sstream>

namespace fs = std::filesystem;

namespace spindrift {

void Simulation::loadWrittenTime(double time, const std::string& timeName) {
    const fs::path dir = case_.dir / timeName;
    const ParticleSet saved = readVtp(dir / "fluid.vtp");
    auto& fluid = fluid_->particles;
    fluid.resize(saved.size());
    fluid.id() = saved.id();
    for (const auto& f : saved.scalarFields())
        if (auto* mine = fluid.findScalar(f->name)) *mine = f->data;
    for (const auto& f : saved.vectorFields())
        if (auto* mine = fluid.findVector(f->name)) *mine = f->data;
    fluid.position() = saved.position();
    // the exact time and step of uniform/time (a name holds 6 digits); a time without it (written
    // by an older version) keeps the name's value
    scene_.time = time;
    scene_.step = 0;
    if (fs::exists(dir / "uniform/time")) {
        const Dictionary t = Dictionary::fromFile(dir / "uniform/time");
        scene_.time = t.get<double>("value");
        scene_.step = t.get<long>("index");
        lastDeltaT_ = t.get<double>("deltaT");
    }
    restorePassiveSystems(dir);
    if (fs::exists(dir / "uniform/bodies")) readBodies(dir);
    ++scene_.stateVersion; // another state: what was sampled of the last one is stale
    updateLists(scene_.time);
}

namespace {

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t");
    if (b == std::string::npos) return "";
    return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

// A number that is the whole of 'text'.
bool parseNumber(const std::string& text, double& value) {
    if (text.empty()) return false;
    char* end = nullptr;
    value = std::strtod(text.c_str(), &end);
    return end && *end == '\0' && std::isfinite(value);
}

bool near(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(b)); }

std::string joinNames(const std::vector<std::pair<double, std::string>>& times) {
    std::string s;
    for (const auto& t : times) s += (s.empty() ? "" : " ") + t.second;
    return s;
}

} // namespace

std::vector<std::pair<double, std::string>> selectTimes(const std::vector<std::pair<double, std::string>>& written,
                                                        const std::string& selection) {
    if (trim(selection).empty()) return written;
    std::vector<bool> chosen(written.size(), false);
    std::istringstream items(selection);
    for (std::string item; std::getline(items, item, ',');) {
        item = trim(item);
        const auto bad = [&] {
            return std::runtime_error("-time '" + selection + "': '" + item +
                                      "' is not a time, a range a:b (:b, a:) or latestTime");
        };
        if (item == "latestTime") {
            if (!written.empty()) chosen.back() = true;
            continue;
        }
        const auto colon = item.find(':');
        if (colon == std::string::npos) {
            double v = 0;
            if (!parseNumber(item, v)) throw bad();
            for (std::size_t k = 0; k < written.size(); ++k)
                if (written[k].second == item || near(written[k].first, v)) chosen[k] = true;
            continue;
        }
        const std::string from = trim(item.substr(0, colon)), to = trim(item.substr(colon + 1));
        double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
        if ((!from.empty() && !parseNumber(from, lo)) || (!to.empty() && !parseNumber(to, hi)) ||
            to.find(':') != std::string::npos)
            throw bad();
        for (std::size_t k = 0; k < written.size(); ++k) {
            const double t = written[k].first;
            if ((t >= lo || near(t, lo)) && (t <= hi || near(t, hi))) chosen[k] = true;
        }
    }
    std::vector<std::pair<double, std::string>> out;
    for (std::size_t k = 0; k < written.size(); ++k)
        if (chosen[k]) out.push_back(written[k]);
    return out;
}

void postProcess(Simulation& sim, const PostProcessRequest& request) {
    const Case& c = sim.caseFiles();
    const Dictionary& control = c.controlDict;
    const Dictionary* functions = control.findDict("functions");
    std::vector<std::string> names = functions ? functions->keywords() : std::vector<std::string>{};
    if (names.empty())
        throw InputError(functions ? functions->where() : control.where(),
                         "-postProcess: system/controlDict names no function object to run (functions { <name> "
                         "{ type probes; ... } })",
                         "functions");
    if (!request.function.empty()) {
        if (std::find(names.begin(), names.end(), request.function) == names.end()) {
            std::string list;
            for (const auto& n : names) list += (list.empty() ? "" : " ") + n;
            const std::string closest = closestMatch(request.function, names);
            throw InputError(functions->where(),
                             "-func '" + request.function + "': no function object of that name in controlDict's "
                                 "functions (" + list + ")" +
                                 (closest.empty() ? "" : "; did you mean '" + closest + "'?"),
                             "functions");
        }
        names = {request.function};
    }
    const auto written = CaseWriter(c.dir).existingTimes();
    if (written.empty())
        throw std::runtime_error("-postProcess: no written time in " + c.dir.string() + " (run the case first)");
    const auto times = selectTimes(written, request.times);
    if (times.empty())
        throw std::runtime_error("-time '" + request.times + "' selects none of the written times (" +
                                 joinNames(written) + ")");

    // Each object from its controlDict entry, sampling at every call (writeControl writeTime); the
    // run's own interval means nothing here: the written times are all there is.
    auto& registry = ModelRegistry::instance();
    Scene& scene = sim.scene();
    std::vector<std::unique_ptr<Dictionary>> dicts;
    std::vector<std::unique_ptr<FunctionObject>> objects;
    for (const auto& name : names) {
        dicts.push_back(std::make_unique<Dictionary>(functions->subDict(name)));
        Dictionary& d = *dicts.back();
        d.set("writeControl", "writeTime");
        d.markUsed("writeControl"); // an object without a sampling schedule reads neither
        d.markUsed("writeInterval");
        objects.push_back(registry.create<FunctionObject>(d, scene.physics, scene.constants, nullptr, c.dir, name));
        objects.back()->require(scene);
    }
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    log::info("\nPost-processing " + std::to_string(times.size()) + (times.size() == 1 ? " time" : " times") + " (" +
              times.front().second + " to " + times.back().second + ") with " + list + "\n");
    for (std::size_t k = 0; k < times.size(); ++k) {
        sim.loadWrittenTime(times[k].first, times[k].second);
        // the forces of the written state (forces): one evaluation there, with the step size the
        // run took last (an iterative solver's pressure depends on it and on its warm start)
        if (scene.reactions.anyWanted()) sim.evaluate(scene.time, Scalar(sim.lastDeltaT()));
        for (auto& o : objects) {
            if (k == 0) o->start(scene, scene.time);
            else o->execute(scene, true);
        }
        log::info("Time = " + times[k].second);
    }
    for (auto& o : objects) o->end(scene);
    std::string where;
    for (const auto& n : names)
        where += "\n    " + (c.dir / "postProcessing" / n / CaseWriter::timeName(times.front().first)).string();
    log::info("\nEnd: post-processed " + std::to_string(times.size()) + (times.size() == 1 ? " time" : " times") +
              "; output in" + where);
}

} // namespace spindrift
