// spindriftStress — numerical stability of model combinations.
//
//   spindriftStress [-vary "pressure.type=wcsph,isobaric"]... [-combination "k=v k=v ..."]...
//                   [-quick] [-tests stillWater,maxDeltaT,jitter,impact] [-output DIR] [-threads 1]
//
// Every combination (the same -vary / -combination syntax as spindriftBench; keys are
// dictionary paths such as kernel.type, pressure.type, viscosity.alpha) is run through four
// generated 2D cases, each in a child process (a crash is a result, not the end):
//  (a) stillWater: water at rest, depth H = 0.2 m in a 0.4 m wide tank, for 60 s (-quick: 2 s):
//      max speed, density error and drift of the free surface (waterLevel gauges) over time.
//  (b) maxDeltaT: the same tank with a fixed Δt for 1 s (-quick: 0.3 s); the largest stable Δt
//      by doubling/halving from 0.25 h/c and then bisection to 10 %. Unstable = the solver
//      stops on a blow-up (a value not finite, a particle far outside, or a density error
//      beyond -densityBound), a particle leaves the tank, or the kinetic energy in the last
//      quarter of the run exceeds twice its maximum in the first half (still water gaining
//      energy beyond its settling transient and sloshing). The search doubles Δt from 0.25 h/c0
//      (c0 = 20 m/s, the tank's weakly compressible sound speed) while stable (and, when
//      unstable there, first looks for a stable step above it, as incompressible solvers may only
//      be stable at larger steps), else halves it, then bisects to 10 %.
//  (c) jitter: a periodic 0.2 m square lattice at rest, no gravity, every particle displaced by
//      10–20 % of the spacing in a random direction (-seed): clustering measured by the
//      minimum pair distance over the spacing over time, and the radial distribution g(r) at
//      the end.
//  (d) impact: a 0.1 m square block thrown at 10 m/s at the wall of a closed tank (c0 = 100
//      m/s): survival, peak density error, particles escaping the tank, kinetic energy
//      against its initial value (it must not grow).
// Base models (changed by the overrides): wendlandC2 (support 2.6 dx), wcsph (γ 7, c0 as
// above, negative pressure clamped), artificial viscosity (α 0.05, same c0), symplecticEuler,
// akinci walls (volume lattice). Switching a model's type gives it built-in presets with the case's sound speed
// (wcsph/isobaric: gamma 7, soundSpeed, clampNegativePressure; artificial: alpha 0.05,
// soundSpeed; pereaCordero viscosity: mu 0.26 (the paper's), dampingScale 0.1), or the ones of
// -presets FILE (benchDict `presets { }` syntax).
//
// Output in <output> (default ./stress): stress_<test>.csv, series/<test>/<combination>.*.dat,
// stress_<test>.png (python3 + matplotlib) and a summary on stdout.
#include "BenchSupport.hpp"
#include "CaseWriter.hpp"
#include "Log.hpp"

#include <algorithm>
#include <boost/program_options.hpp>
#include <cmath>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <sstream>

namespace po = boost::program_options;
namespace fs = std::filesystem;
using namespace spindrift;
using namespace spindrift::bench;

namespace {

constexpr double supportFactor = 2.6;

std::string num(double v) {
    std::ostringstream o;
    o << std::setprecision(10) << v;
    return o.str();
}

std::string header(const std::string& object) {
    return "FoamFile\n{\n    version     2.0;\n    format      ascii;\n    class       dictionary;\n    object      " +
           object + ";\n}\n\n";
}

struct CaseText {
    std::string controlDict, geometry;
    double dx = 0.01, c0 = 20;
    bool gravity = true, walls = true;
};

struct Settings {
    fs::path output, solver;
    int threads = 1;
    double timeout = 0;
    bool quick = false, keep = false;
    unsigned seed = 1;
    double densityBound = 0.25;
    int resolution = 0; // 0 = the test's default
    double stillWaterTime = 0;
    std::string userPresets;
};

std::string presetsText(double c0) {
    const std::string c = num(c0);
    return "pressure\n{\n"
           "    wcsph { gamma 7; soundSpeed " + c + "; clampNegativePressure yes; }\n"
           "    isobaric { gamma 7; soundSpeed " + c + "; clampNegativePressure yes; }\n"
           "}\nviscosity\n{\n"
           "    artificial { alpha 0.05; soundSpeed " + c + "; }\n"
           "    pereaCordero { mu 0.26; dampingScale 0.1; }\n"
           "}\n";
}

void writeCase(const fs::path& dir, const CaseText& t) {
    fs::create_directories(dir / "system");
    fs::create_directories(dir / "constant");
    const std::string c = num(t.c0);
    std::ofstream(dir / "system/controlDict") << header("controlDict") << t.controlDict;
    std::ofstream(dir / "system/sphSchemes")
        << header("sphSchemes") << "kernel\n{\n    type wendlandC2;\n}\n"
        << "pressure\n{\n    type wcsph;\n    gamma 7;\n    soundSpeed " << c << ";\n    clampNegativePressure yes;\n}\n"
        << "viscosity\n{\n    type artificial;\n    alpha 0.05;\n    soundSpeed " << c << ";\n}\n"
        << "integrator\n{\n    type symplecticEuler;\n}\n"
        << (t.walls ? "boundary\n{\n    type akinci;\n    volume lattice;\n}\n" : "");
    std::ofstream(dir / "constant/fluidProperties")
        << header("fluidProperties") << "dimension 2;\nrho0 1000;\nviscosity 1e-6;\ngravity (0 " << (t.gravity ? "-9.81" : "0")
        << " 0);\nparticleSpacing " << num(t.dx) << ";\nsupportRadius " << supportFactor << ";\n";
    std::ofstream(dir / "constant/geometry") << header("geometry") << t.geometry;
}

class Harness {
public:
    Harness(Settings s, const std::vector<Combination>& combos) : s_(std::move(s)) {
        const auto names = uniqueNames(combos);
        for (std::size_t k = 0; k < combos.size(); ++k) names_[combinationLabel(combos[k])] = names[k];
    }
    std::string name(const Combination& c) const { return names_.at(combinationLabel(c)); }

    // Writes the case for 'combination' under runs/<test>/<name>[/<suffix>] and applies the overrides.
    fs::path prepare(const std::string& test, const Combination& c, const CaseText& t, const std::string& suffix = "") {
        fs::path dir = s_.output / "runs" / test / name(c);
        if (!suffix.empty()) dir /= suffix;
        fs::remove_all(dir);
        writeCase(dir, t);
        const Dictionary presets = Dictionary::fromString(presetsText(t.c0) + s_.userPresets, "<presets>");
        CaseDictionaries dicts(dir);
        dicts.apply(c, &presets);
        dicts.write();
        return dir;
    }

    RunOutcome run(const fs::path& dir, bool dryRun = false) {
        std::vector<std::string> argv{s_.solver.string(), "-case", ".", "-threads", std::to_string(s_.threads)};
        if (dryRun) argv.push_back("-dryRun");
        const fs::path log = dir / (dryRun ? "log.dryRun" : "log.spindrift");
        const auto pr = runProcess(argv, dir, log, {"OMP_NUM_THREADS=" + std::to_string(s_.threads)}, s_.timeout);
        RunOutcome o = runOutcome(pr, log, s_.timeout, {.endLine = !dryRun, .anyBlowUp = true});
        // the run directory goes: where its last good state was written means nothing
        if (o.status == "unstable") o.note = o.note.substr(0, o.note.find(". The last good state"));
        return o;
    }

    // Writes the case for 'c' (prepare, into 'dir') and runs it: the solver, or 'execute' when
    // given. An error on the way is a "failed" outcome.
    RunOutcome attempt(const std::string& test, const Combination& c, const CaseText& t, fs::path& dir,
                       const std::function<RunOutcome(const fs::path&)>& execute = nullptr) {
        try {
            dir = prepare(test, c, t);
            return execute ? execute(dir) : run(dir);
        } catch (const std::exception& e) {
            return {"failed", e.what(), {}};
        }
    }

    // Prints the combination's label; for one naming a model that is not built, writes its
    // "unavailable" row to 'csv' and returns false.
    bool available(const Combination& c, CsvWriter& csv) const {
        printLabel(c);
        const std::string missing = unavailableModel(c);
        if (missing.empty()) return true;
        std::vector<std::string> row(csv.columns());
        row[0] = name(c);
        row[1] = combinationLabel(c);
        row[2] = "unavailable";
        row.back() = missing + " is not built";
        csv.row(row);
        std::cout << "unavailable\n";
        return false;
    }

    void finish(const fs::path& dir) {
        if (!s_.keep) fs::remove_all(dir);
    }

    // Copies postProcessing/<name> tables of a run into series/<test>/<combination>.<name>.dat.
    void keepSeries(const fs::path& dir, const std::string& test, const std::string& combo,
                    const std::vector<std::string>& names) {
        const fs::path target = s_.output / "series" / test;
        fs::create_directories(target);
        for (const auto& n : names) {
            const Table t = readPostProcessing(dir, n);
            std::ofstream out(target / (combo + "." + n + ".dat"));
            out << "#";
            for (const auto& c : t.columns) out << ' ' << c;
            out << '\n' << std::setprecision(10);
            for (const auto& r : t.rows) {
                for (std::size_t i = 0; i < r.size(); ++i) out << (i ? " " : "") << r[i];
                out << '\n';
            }
        }
    }

    const Settings& settings() const { return s_; }

private:
    Settings s_;
    std::map<std::string, std::string> names_;
};

// ---------------------------------------------------------------------------------------------
// tank scenarios (a) and (b)

struct Tank {
    double H = 0.2, W = 0.4, dx = 0.02, c0 = 20;
    CaseText text(const std::string& control) const {
        CaseText t;
        t.dx = dx;
        t.c0 = c0;
        t.controlDict = control;
        t.geometry = "fluid\n{\n    water\n    {\n        type box;\n        min (0 0 0);\n        max (" + num(W) + " " + num(H) +
                     " 0);\n    }\n}\nwalls\n{\n    tank\n    {\n        type container;\n        min (0 0 0);\n        max (" +
                     num(W) + " " + num(1.5 * H) + " 0);\n        layers 3;\n        open (yMax);\n    }\n}\n";
        return t;
    }
};

double mean(const std::vector<double>& v, std::size_t from, std::size_t to) {
    double s = 0;
    std::size_t n = 0;
    for (std::size_t i = from; i < std::min(to, v.size()); ++i)
        if (std::isfinite(v[i])) {
            s += v[i];
            ++n;
        }
    return n ? s / double(n) : std::nan("");
}

double maxOf(const std::vector<double>& v, std::size_t from, std::size_t to) {
    double m = -std::numeric_limits<double>::infinity();
    for (std::size_t i = from; i < std::min(to, v.size()); ++i)
        if (std::isfinite(v[i])) m = std::max(m, v[i]);
    return m;
}

void stillWater(Harness& h, const std::vector<Combination>& combos) {
    const auto& s = h.settings();
    Tank tank;
    const int n = s.resolution > 0 ? s.resolution : (s.quick ? 10 : 20);
    tank.dx = tank.H / n;
    const double T = s.stillWaterTime > 0 ? s.stillWaterTime : (s.quick ? 2.0 : 60.0);
    const std::string sample = num(T / 500);
    const std::string control = "application spindrift;\nstartFrom startTime;\nstartTime 0;\nendTime " + num(T) +
                                ";\ndeltaT 1e-4;\nadjustTimeStep yes;\nmaxCo 0.15;\nmaxDeltaT 1e-3;\n"
                                "writeControl adjustableRunTime;\nwriteInterval " + num(T) + ";\n"
                                "writeFields (velocity pressure density);\nblowUpDensityError " + num(s.densityBound) + ";\n"
                                "functions\n{\n    stats { type fieldStats; writeControl runTime; writeInterval " + sample +
                                "; }\n    level { type waterLevel; gaugeLocations ((0.1 0 0) (0.2 0 0) (0.3 0 0)); "
                                "writeControl runTime; writeInterval " + sample + "; }\n}\n";
    std::cout << "\n(a) stillWater: depth " << tank.H << " m, dx " << tank.dx << " m (" << n * 2 * n << " particles), "
              << T << " s\n";
    CsvWriter csv(s.output / "stress_stillWater.csv",
                  {"combination", "label", "status", "wallTime_s", "steps", "maxSpeedEnd", "maxSpeedLate",
                   "rhoErrMaxLate_pct", "levelDrift_dx", "kineticEnergyEnd", "note"});
    for (const auto& c : combos) {
        const std::string name = h.name(c);
        if (!h.available(c, csv)) continue;
        std::vector<std::string> row{name, combinationLabel(c)};
        fs::path dir;
        const RunOutcome o = h.attempt("stillWater", c, tank.text(control), dir);
        std::string speedEnd, speedLate, rhoLate, drift, keEnd;
        if (!dir.empty() && fs::exists(dir / "postProcessing/stats")) {
            const Table stats = readPostProcessing(dir, "stats");
            const Table level = readPostProcessing(dir, "level");
            const auto speed = stats.values("maxSpeed"), rho = stats.values("rhoErrMax"),
                       ke = stats.values("kineticEnergy");
            const std::size_t m = speed.size();
            if (m > 10 && o.status == "ok") {
                speedEnd = csvNumber(speed.back(), 4);
                speedLate = csvNumber(mean(speed, m - m / 10, m), 4);
                rhoLate = csvNumber(maxOf(rho, m / 2, m), 4); // fieldStats writes %
                keEnd = csvNumber(ke.back(), 4);
                // average over the gauges of (late level − level after settling)
                double d = 0;
                int gauges = 0;
                for (const auto& col : level.columns)
                    if (col.rfind("level", 0) == 0) {
                        const auto v = level.values(col);
                        const std::size_t k = v.size();
                        d += mean(v, k - k / 10, k) - mean(v, k / 10, k / 5);
                        ++gauges;
                    }
                drift = csvNumber(d / gauges / tank.dx, 4);
            }
            h.keepSeries(dir, "stillWater", name, {"stats", "level"});
        }
        row.insert(row.end(), {o.status, o.end.found ? csvNumber(o.end.wallSeconds, 4) : "",
                               o.end.found ? std::to_string(o.end.steps) : "", speedEnd, speedLate, rhoLate, drift, keEnd,
                               o.note});
        csv.row(row);
        std::cout << o.status;
        if (o.status == "ok")
            std::cout << "  max speed " << speedEnd << " m/s, late density error " << rhoLate << " %, level drift " << drift
                      << " dx";
        else std::cout << "  " << o.note;
        std::cout << std::endl;
        if (!dir.empty()) h.finish(dir);
    }
}

void maxDeltaT(Harness& h, const std::vector<Combination>& combos) {
    const auto& s = h.settings();
    Tank tank;
    const int n = s.resolution > 0 ? s.resolution : (s.quick ? 10 : 20);
    tank.dx = tank.H / n;
    const double T = s.quick ? 0.3 : 1.0;
    const double hSupport = supportFactor * tank.dx, dtRef = hSupport / tank.c0;
    const double cap = T / 30;
    std::cout << "\n(b) maxDeltaT: the still-water tank (dx " << tank.dx << " m) with a fixed step for " << T
              << " s; reference h/c0 = " << dtRef << " s\n";
    CsvWriter csv(s.output / "stress_maxDeltaT.csv", {"combination", "label", "status", "maxStableDeltaT_s",
                                                      "courantOnH", "firstUnstableDeltaT_s", "runs", "reason", "note"});
    for (const auto& c : combos) {
        const std::string name = h.name(c);
        if (!h.available(c, csv)) continue;
        int runs = 0;
        std::string lastReason, failure;
        // true = stable
        auto stable = [&](double dt) {
            ++runs;
            const std::string control = "application spindrift;\nstartFrom startTime;\nstartTime 0;\nendTime " + num(T) +
                                        ";\ndeltaT " + num(dt) + ";\nadjustTimeStep no;\n"
                                        "writeControl timeStep;\nwriteInterval 100000000;\nblowUpDensityError " +
                                        num(s.densityBound) + ";\nfunctions\n{\n    stats { type fieldStats; writeControl "
                                        "runTime; writeInterval " + num(T / 100) + "; }\n}\n";
            const fs::path dir = h.prepare("maxDeltaT", c, tank.text(control), "dt" + num(dt));
            const RunOutcome o = h.run(dir);
            bool ok = o.status == "ok";
            std::string reason = ok ? "" : o.status + ": " + o.note;
            if (o.status == "failed" || o.status == "timeout") failure = reason;
            if (ok) {
                const Table st = readPostProcessing(dir, "stats");
                const auto xMin = st.values("xMin"), xMax = st.values("xMax"), yMin = st.values("yMin"),
                           ke = st.values("kineticEnergy");
                const double margin = 3 * tank.dx;
                for (std::size_t i = 0; i < xMin.size() && ok; ++i)
                    if (xMin[i] < -margin || xMax[i] > tank.W + margin || yMin[i] < -margin) {
                        ok = false;
                        reason = "a particle left the tank";
                    }
                const std::size_t m = ke.size();
                if (ok && m >= 8) {
                    // sloshing after the settling transient keeps its energy: growth means
                    // more than twice the first half's maximum in the last quarter
                    const double first = maxOf(ke, 0, m / 2), last = maxOf(ke, m - m / 4, m);
                    if (last > 2 * first && last > 1e-12) {
                        ok = false;
                        reason = "kinetic energy grows (" + num(last) + " > " + num(first) + " J/m)";
                    }
                }
            }
            if (!ok) lastReason = reason;
            h.finish(dir);
            return ok;
        };
        // bracket: from 0.25 h/c0 up by doubling (also when unstable there: incompressible
        // solvers may only be stable at larger steps), else down by halving
        const double start = 0.25 * dtRef;
        double lo = 0, hi = std::numeric_limits<double>::infinity(), dt = start;
        if (stable(dt)) lo = dt;
        else {
            while (lo == 0 && dt * 2 <= cap && failure.empty()) {
                dt *= 2;
                if (stable(dt)) lo = dt;
            }
        }
        if (lo > 0) {
            while (std::isinf(hi) && dt * 2 <= cap && failure.empty()) {
                dt *= 2;
                (stable(dt) ? lo : hi) = dt;
            }
        } else {
            hi = dt = start;
            while (lo == 0 && dt > dtRef / 64 && failure.empty()) {
                dt /= 2;
                (stable(dt) ? lo : hi) = dt;
            }
        }
        while (lo > 0 && std::isfinite(hi) && hi / lo > 1.1 && failure.empty()) {
            const double mid = std::sqrt(lo * hi);
            (stable(mid) ? lo : hi) = mid;
        }
        std::string status = !failure.empty() ? "failed" : lo == 0 ? "unstable" : std::isinf(hi) ? "atCap" : "ok";
        csv.row({name, combinationLabel(c), status, lo > 0 ? csvNumber(lo, 4) : "", lo > 0 ? csvNumber(lo / dtRef, 3) : "",
                 std::isfinite(hi) ? csvNumber(hi, 4) : "", std::to_string(runs), lastReason, failure});
        std::cout << status << "  max stable dt " << (lo > 0 ? csvNumber(lo, 3) : "none") << " s (" << csvNumber(lo / dtRef, 3)
                  << " h/c0), " << runs << " runs" << (status == "atCap" ? " (stable up to T/30)" : "")
                  << (failure.empty() ? "" : "  " + failure) << std::endl;
    }
}

// ---------------------------------------------------------------------------------------------
// (c) jittered lattice

struct RdfResult {
    std::vector<double> r, g;
    double minPair = 0, clusterFraction = 0;
};

// Radial distribution in a periodic square of side L (2D), r in units of dx.
RdfResult radialDistribution(const std::vector<Vec3>& x, double L, double dx) {
    RdfResult out;
    const double rMax = 3 * dx, bin = 0.05 * dx;
    const int bins = int(rMax / bin);
    std::vector<double> counts(bins, 0.0);
    const std::size_t n = x.size();
    double minPair = std::numeric_limits<double>::infinity();
    std::size_t clustered = 0;
    for (std::size_t i = 0; i < n; ++i) {
        double nearest = std::numeric_limits<double>::infinity();
        for (std::size_t j = 0; j < n; ++j) {
            if (i == j) continue;
            double ddx = x[i][0] - x[j][0], ddy = x[i][1] - x[j][1];
            ddx -= L * std::round(ddx / L);
            ddy -= L * std::round(ddy / L);
            const double r = std::sqrt(ddx * ddx + ddy * ddy);
            nearest = std::min(nearest, r);
            if (r < rMax) counts[std::size_t(r / bin)] += 1;
        }
        minPair = std::min(minPair, nearest);
        if (nearest < 0.5 * dx) ++clustered;
    }
    const double density = double(n) / (L * L);
    for (int b = 0; b < bins; ++b) {
        const double r0 = b * bin, r1 = r0 + bin;
        const double shell = M_PI * (r1 * r1 - r0 * r0);
        out.r.push_back((r0 + 0.5 * bin) / dx);
        out.g.push_back(counts[b] / (double(n) * density * shell));
    }
    out.minPair = minPair / dx;
    out.clusterFraction = double(clustered) / double(n);
    return out;
}

void jitter(Harness& h, const std::vector<Combination>& combos) {
    const auto& s = h.settings();
    const int n = s.resolution > 0 ? int(1.6 * s.resolution) : (s.quick ? 16 : 32);
    const double L = 0.2, dx = L / n, c0 = 10;
    const double T = s.quick ? 0.2 : 1.0;
    CaseText t;
    t.dx = dx;
    t.c0 = c0;
    t.gravity = false;
    t.walls = false;
    // first step at the Courant limit (an incompressible solver's first step would otherwise be
    // the tiny initial deltaT, turning the jitter's correction Δx/Δt into a huge velocity);
    // blow-up above 10 c0 whatever the model's own sound speed
    t.controlDict = "application spindrift;\nstartFrom latestTime;\nstartTime 0;\nendTime " + num(T) +
                    ";\ndeltaT " + num(0.15 * supportFactor * dx / c0) + ";\nadjustTimeStep yes;\nmaxCo 0.15;\n"
                    "maxDeltaT 1e-3;\nblowUpSpeed " + num(10 * c0) + ";\nwriteControl adjustableRunTime;\n"
                    "writeInterval " + num(T) + ";\nwriteFields (velocity pressure density);\n"
                    "functions\n{\n    stats { type fieldStats; writeControl runTime; writeInterval " + num(T / 200) + "; }\n}\n";
    t.geometry = "fluid\n{\n    block\n    {\n        type box;\n        min (0 0 0);\n        max (" + num(L) + " " + num(L) +
                 " 0);\n    }\n}\nperiodic\n{\n    x (0 " + num(L) + ");\n    y (0 " + num(L) + ");\n}\n";
    std::cout << "\n(c) jitter: periodic " << n << " x " << n << " lattice, displacements 10-20 % of dx (seed " << s.seed
              << "), no gravity, " << T << " s\n";
    CsvWriter csv(s.output / "stress_jitter.csv",
                  {"combination", "label", "status", "wallTime_s", "minPairStart_dx", "minPairMin_dx", "minPairEnd_dx",
                   "clusterFractionEnd", "rdfPeak_r_dx", "rdfPeak_g", "kineticEnergyMax", "kineticEnergyEnd", "note"});
    for (const auto& c : combos) {
        const std::string name = h.name(c);
        if (!h.available(c, csv)) continue;
        fs::path dir;
        // the dry run writes the lattice, displaced here before the run
        const RunOutcome o = h.attempt("jitter", c, t, dir, [&](const fs::path& d) {
            const RunOutcome dry = h.run(d, true);
            if (dry.status != "ok") return dry;
            const fs::path file = d / "0" / "fluid.vtp";
            ParticleSet set = readVtp(file);
            std::mt19937 rng(s.seed);
            std::uniform_real_distribution<double> amplitude(0.1, 0.2), angle(0, 2 * M_PI);
            for (auto& p : set.position()) {
                const double a = amplitude(rng) * dx, phi = angle(rng);
                p[0] = std::fmod(p[0] + a * std::cos(phi) + L, L);
                p[1] = std::fmod(p[1] + a * std::sin(phi) + L, L);
            }
            writeVtp(file, set);
            return h.run(d);
        });
        std::vector<std::string> row{name, combinationLabel(c), o.status, o.end.found ? csvNumber(o.end.wallSeconds, 4) : ""};
        if (o.status == "ok") {
            const Table st = readPostProcessing(dir, "stats");
            const auto pair = st.values("minPairDistance"), ke = st.values("kineticEnergy");
            double pMin = std::numeric_limits<double>::infinity();
            for (double v : pair)
                if (std::isfinite(v)) pMin = std::min(pMin, v);
            const auto times = CaseWriter(dir).existingTimes();
            const ParticleSet last = readVtp(dir / times.back().second / "fluid.vtp");
            const RdfResult rdf = radialDistribution(last.position(), L, dx);
            const auto peak = std::max_element(rdf.g.begin(), rdf.g.end()) - rdf.g.begin();
            row.insert(row.end(), {csvNumber(pair.front() / dx, 4), csvNumber(pMin / dx, 4), csvNumber(pair.back() / dx, 4),
                                   csvNumber(rdf.clusterFraction, 4), csvNumber(rdf.r[peak], 3), csvNumber(rdf.g[peak], 4),
                                   csvNumber(maxOf(ke, 0, ke.size()), 4), csvNumber(ke.back(), 4), ""});
            h.keepSeries(dir, "jitter", name, {"stats"});
            std::ofstream out(s.output / "series" / "jitter" / (name + ".rdf.dat"));
            out << "# r_dx g\n";
            for (std::size_t i = 0; i < rdf.r.size(); ++i) out << rdf.r[i] << ' ' << rdf.g[i] << '\n';
            std::cout << "ok  min pair distance " << csvNumber(pair.front() / dx, 3) << " -> " << csvNumber(pair.back() / dx, 3)
                      << " dx (lowest " << csvNumber(pMin / dx, 3) << "), clustered " << csvNumber(100 * rdf.clusterFraction, 3)
                      << " %" << std::endl;
        } else {
            row.insert(row.end(), {"", "", "", "", "", "", "", "", o.note});
            std::cout << o.status << "  " << o.note << std::endl;
        }
        csv.row(row);
        if (!dir.empty()) h.finish(dir);
    }
}

// ---------------------------------------------------------------------------------------------
// (d) impact

void impact(Harness& h, const std::vector<Combination>& combos) {
    const auto& s = h.settings();
    const int n = s.resolution > 0 ? s.resolution : (s.quick ? 10 : 20);
    const double block = 0.1, dx = block / n, V = 10, W = 0.6, Ht = 0.3, c0 = 10 * V;
    const double T = s.quick ? 0.08 : 0.15;
    CaseText t;
    t.dx = dx;
    t.c0 = c0;
    t.controlDict = "application spindrift;\nstartFrom startTime;\nstartTime 0;\nendTime " + num(T) +
                    ";\ndeltaT 1e-5;\nadjustTimeStep yes;\nmaxCo 0.15;\nmaxDeltaT 1e-3;\nwriteControl adjustableRunTime;\n"
                    "writeInterval " + num(T) + ";\nwriteFields (velocity pressure density);\nblowUpDensityError 0.5;\n"
                    "functions\n{\n    stats { type fieldStats; writeControl runTime; writeInterval " + num(T / 400) + "; }\n}\n";
    t.geometry = "fluid\n{\n    block\n    {\n        type box;\n        min (0.05 0 0);\n        max (" + num(0.05 + block) + " " +
                 num(block) + " 0);\n        velocity (" + num(V) + " 0 0);\n    }\n}\nwalls\n{\n    tank\n    {\n"
                 "        type container;\n        min (0 0 0);\n        max (" + num(W) + " " + num(Ht) +
                 " 0);\n        layers 3;\n    }\n}\n";
    std::cout << "\n(d) impact: " << n << " x " << n << " block at " << V << " m/s against a wall (c0 " << c0 << " m/s), " << T
              << " s\n";
    CsvWriter csv(s.output / "stress_impact.csv",
                  {"combination", "label", "status", "wallTime_s", "steps", "rhoErrMax_pct", "kineticEnergyMaxAfterImpact",
                   "kineticEnergyEnd", "escaped", "minPairMin_dx", "note"});
    for (const auto& c : combos) {
        const std::string name = h.name(c);
        if (!h.available(c, csv)) continue;
        fs::path dir;
        const RunOutcome o = h.attempt("impact", c, t, dir);
        std::vector<std::string> row{name, combinationLabel(c), o.status, o.end.found ? csvNumber(o.end.wallSeconds, 4) : "",
                                     o.end.found ? std::to_string(o.end.steps) : ""};
        if (!dir.empty() && fs::exists(dir / "postProcessing/stats")) {
            const Table st = readPostProcessing(dir, "stats");
            const auto time = st.values("Time"), rho = st.values("rhoErrMax"), ke = st.values("kineticEnergy"),
                       xMin = st.values("xMin"), xMax = st.values("xMax"), yMin = st.values("yMin"),
                       yMax = st.values("yMax"), pair = st.values("minPairDistance");
            const double ke0 = ke.front();
            // first contact: the block's front reaches the wall's support region
            std::size_t contact = 0;
            while (contact < xMax.size() && xMax[contact] < W - supportFactor * dx) ++contact;
            const double margin = 3 * dx;
            bool escaped = false;
            for (std::size_t i = 0; i < xMin.size(); ++i)
                escaped = escaped || xMin[i] < -margin || xMax[i] > W + margin || yMin[i] < -margin || yMax[i] > Ht + margin;
            double pMin = std::numeric_limits<double>::infinity();
            for (double v : pair)
                if (std::isfinite(v)) pMin = std::min(pMin, v);
            row.insert(row.end(), {csvNumber(maxOf(rho, 0, rho.size()), 4), // %
                                   contact < ke.size() ? csvNumber(maxOf(ke, contact, ke.size()) / ke0, 4) : "",
                                   csvNumber(ke.back() / ke0, 4), escaped ? "yes" : "no", csvNumber(pMin / dx, 4), o.note});
            h.keepSeries(dir, "impact", name, {"stats"});
            std::cout << o.status << "  max density error " << row[5] << " %, KE max after impact " << row[6]
                      << " KE0, end " << row[7] << " KE0" << (escaped ? ", particles escaped" : "")
                      << (o.status == "ok" ? "" : "  " + o.note) << std::endl;
            (void)time;
        } else {
            row.insert(row.end(), {"", "", "", "", "", o.note});
            std::cout << o.status << "  " << o.note << std::endl;
        }
        csv.row(row);
        if (!dir.empty()) h.finish(dir);
    }
}

} // namespace

int main(int argc, char** argv) {
    po::options_description options(
        "Usage: spindriftStress [-vary key=v1,v2,...]... [-combination \"k=v k=v\"]... [options]\n"
        "Runs still water, the largest stable time step, a jittered lattice and a high-speed impact for every model\n"
        "combination.\nOptions");
    options.add_options()
        ("help", "print this help and exit")
        ("vary", po::value<std::vector<std::string>>()->composing(),
         "key=v1,v2,... : a dictionary entry and its values (repeatable), e.g. pressure.type=wcsph,isobaric")
        ("combination", po::value<std::vector<std::string>>()->composing(),
         "\"key=value key=value ...\": one more combination (repeatable)")
        ("quick", "short runs at coarse resolution (CI)")
        ("tests", po::value<std::string>()->default_value("stillWater,maxDeltaT,jitter,impact"), "tests to run")
        ("output", po::value<std::string>()->default_value("stress"), "output directory")
        ("threads", po::value<int>()->default_value(1), "OpenMP threads per run")
        ("timeout", po::value<double>()->default_value(0), "seconds after which a run is stopped (0 = none)")
        ("seed", po::value<unsigned>()->default_value(1), "random seed of the jittered lattice")
        ("densityBound", po::value<double>()->default_value(0.25),
         "density error (fraction) beyond which a still-water run counts as blown up")
        ("resolution", po::value<int>()->default_value(0), "particles across the water depth / block (0 = the default)")
        ("stillWaterTime", po::value<double>()->default_value(0), "physical time of (a) in s (0 = 60, -quick 2)")
        ("presets", po::value<std::string>(), "dictionary of model presets (benchDict 'presets' syntax)")
        ("keep", "keep the run directories under <output>/runs")
        ("noPlot", "do not draw the plots");
    po::variables_map vm;
    if (const auto status = parseCommandLine(argc, argv, options, "spindriftStress", vm)) return *status;
    try {
        log::setQuiet(true);
        checkThreadsAndTimeout(vm);
        const auto combos = requestedCombinations(vm);
        Settings s;
        s.output = fs::absolute(vm["output"].as<std::string>());
        s.solver = executableDirectory() / "spindrift";
        s.threads = vm["threads"].as<int>();
        s.timeout = vm["timeout"].as<double>();
        s.quick = vm.count("quick") > 0;
        s.keep = vm.count("keep") > 0;
        s.seed = vm["seed"].as<unsigned>();
        s.densityBound = vm["densityBound"].as<double>();
        s.resolution = vm["resolution"].as<int>();
        s.stillWaterTime = vm["stillWaterTime"].as<double>();
        if (s.resolution != 0 && s.resolution < 4)
            throw std::runtime_error("-resolution " + std::to_string(s.resolution) +
                                     ": give the particles across the water depth (at least 4), or 0 for the default");
        if (!(s.stillWaterTime >= 0) || !std::isfinite(s.stillWaterTime)) {
            std::ostringstream m;
            m << "-stillWaterTime " << s.stillWaterTime << ": give the physical time in s (positive), or 0 for the default";
            throw std::runtime_error(m.str());
        }
        if (!(s.densityBound > 0) || !std::isfinite(s.densityBound)) {
            std::ostringstream m;
            m << "-densityBound " << s.densityBound << ": give a positive fraction (0.25: 25 %)";
            throw std::runtime_error(m.str());
        }
        if (vm.count("presets")) {
            std::ifstream in(vm["presets"].as<std::string>());
            if (!in) throw std::runtime_error("cannot read -presets " + vm["presets"].as<std::string>());
            std::ostringstream text;
            text << in.rdbuf();
            s.userPresets = "\n" + text.str();
        }
        fs::create_directories(s.output);
        std::set<std::string> tests;
        {
            std::istringstream in(vm["tests"].as<std::string>());
            std::string t;
            while (std::getline(in, t, ','))
                if (!t.empty()) {
                    if (t != "stillWater" && t != "maxDeltaT" && t != "jitter" && t != "impact")
                        throw std::runtime_error("unknown test '" + t + "'; valid: stillWater,maxDeltaT,jitter,impact");
                    tests.insert(t);
                }
        }
        std::cout << "spindriftStress: " << combos.size() << " combination(s)" << (s.quick ? " (quick)" : "") << ", "
                  << s.threads << " thread(s) per run, output " << s.output.string() << std::endl;
        Harness h(s, combos);
        if (tests.count("stillWater")) stillWater(h, combos);
        if (tests.count("maxDeltaT")) maxDeltaT(h, combos);
        if (tests.count("jitter")) jitter(h, combos);
        if (tests.count("impact")) impact(h, combos);
        if (!s.keep) fs::remove_all(s.output / "runs");

        if (!vm.count("noPlot") && runPlotScript("spindriftStress", "spindriftStressPlot.py", {s.output.string()}, s.output, 300))
            std::cout << "\nPlots: " << (s.output / "stress_*.png").string() << std::endl;
        std::cout << "Tables: " << (s.output / "stress_*.csv").string() << std::endl;
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "spindriftStress: error: " << e.what() << std::endl;
        return 1;
    }
}
