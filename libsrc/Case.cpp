#include "Case.hpp"

#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace spindrift {

Case Case::read(const fs::path& dir) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw InputError({dir.string(), 0, 0}, "case directory '" + dir.string() + "' does not exist");
    Case c;
    c.dir = dir;
    c.name = fs::weakly_canonical(fs::absolute(dir)).filename().string();
    c.controlDict = Dictionary::fromFile(dir / "system/controlDict");
    c.sphSchemes = Dictionary::fromFile(dir / "system/sphSchemes");
    if (fs::exists(dir / "system/sphSolution", ec))
        c.sphSolution = Dictionary::fromFile(dir / "system/sphSolution");
    else
        c.sphSolution = Dictionary("sphSolution", {(dir / "system/sphSolution").string(), 0, 0});
    c.fluidProperties = Dictionary::fromFile(dir / "constant/fluidProperties");
    c.geometry = Dictionary::fromFile(dir / "constant/geometry");
    return c;
}

PhysicalParameters readPhysicalParameters(const Dictionary& d) {
    PhysicalParameters p;
    const int dim = d.get<int>("dimension");
    if (dim != 2 && dim != 3)
        throw InputError(d.locationOf("dimension"), "dimension must be 2 or 3, not " + std::to_string(dim), "dimension");
    p.dimension = dim;
    p.rho0 = d.get<double>("rho0");
    if (!(p.rho0 > 0)) throw InputError(d.locationOf("rho0"), "rho0 must be positive", "rho0");
    p.nu = d.getOrDefault<double>("viscosity", 0.0);
    if (p.nu < 0) throw InputError(d.locationOf("viscosity"), "viscosity must not be negative", "viscosity");
    p.gravity = d.getOrDefault<Vec3>("gravity", Vec3::Zero());
    if (dim == 2 && p.gravity[2] != 0)
        throw InputError(d.locationOf("gravity"), "gravity must have z = 0 in two dimensions", "gravity");
    p.particleSpacing = d.get<double>("particleSpacing");
    if (!(p.particleSpacing > 0))
        throw InputError(d.locationOf("particleSpacing"), "particleSpacing must be positive", "particleSpacing");
    const double factor = d.getOrDefault<double>("supportRadius", 2.0);
    if (!(factor >= 1.5) || factor > 6) {
        std::ostringstream s;
        s << "supportRadius " << factor << " (in units of particleSpacing) gives too "
          << (factor > 6 ? "many" : "few") << " neighbours; use a value between 1.5 and 6 (typically 2-3)";
        throw InputError(d.locationOf("supportRadius"), s.str(), "supportRadius");
    }
    p.supportRadius = Scalar(factor) * p.particleSpacing;
    d.checkAllKeywordsUsed();
    return p;
}

bool isTimeName(const std::string& name) {
    if (name.empty()) return false;
    char* end = nullptr;
    std::strtod(name.c_str(), &end);
    return end == name.c_str() + name.size();
}

void copyCaseInput(const fs::path& source, const fs::path& target) {
    std::error_code ec;
    if (!fs::is_directory(source, ec)) throw std::runtime_error("case directory '" + source.string() + "' does not exist");
    if (fs::exists(target, ec) && !fs::is_empty(target, ec))
        throw std::runtime_error("'" + target.string() + "' exists already and is not empty");
    fs::create_directories(target);
    for (const auto& entry : fs::directory_iterator(source)) {
        const std::string name = entry.path().filename().string();
        if (name.empty() || name[0] == '.') continue;
        if (entry.is_directory()) {
            if (isTimeName(name) || name == "postProcessing" || name == "run") continue;
        } else {
            const std::string ext = entry.path().extension().string();
            if (name.rfind("log.", 0) == 0 || ext == ".pvd" || ext == ".png" || ext == ".tmp") continue;
        }
        fs::copy(entry.path(), target / name, fs::copy_options::recursive);
    }
}

} // namespace spindrift
