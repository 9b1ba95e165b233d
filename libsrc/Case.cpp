#include "Case.hpp"

#include "Log.hpp"

#include <atomic>
#include <cerrno>
#include <fcntl.h>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

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
    p.supportRadiusFactor = Scalar(factor);
    d.checkAllKeywordsUsed();
    return p;
}

namespace {
// The lock of this process for releaseInSignalHandler: fixed buffers a signal handler may read,
// published by 'lockRegistered' once complete.
char lockPath[4096], lockTempPath[4096], lockContent[300];
std::atomic<bool> lockRegistered{false};

bool copyInto(char* buffer, std::size_t size, const std::string& text) {
    if (text.size() + 1 > size) return false;
    std::memcpy(buffer, text.c_str(), text.size() + 1);
    return true;
}

std::string hostName() {
    char host[256] = {};
    if (gethostname(host, sizeof host - 1) != 0) return "unknown";
    return host;
}
} // namespace

CaseLock::CaseLock(const fs::path& caseDir) : file_(file(caseDir)) {
    const std::string me = std::to_string(getpid()) + " " + hostName();
    // the complete lock written under a name of our own, then linked: link() fails if the lock exists
    fs::path mine = file_;
    mine += '.';
    mine += std::to_string(getpid());
    // a signal that ends the process during set-up (stopAtOnceOnSignalsDuringSetUp) removes the
    // lock if it is this process's (its content says so) and the temporary file; registered
    // here, withdrawn unless this lock ends up owning the file
    struct Registration {
        bool mine = false;
        const bool& owner;
        ~Registration() {
            if (mine && !owner) lockRegistered.store(false);
        }
    } registration{false, owner_};
    if (!lockRegistered.load() && copyInto(lockPath, sizeof lockPath, file_.string()) &&
        copyInto(lockTempPath, sizeof lockTempPath, mine.string()) &&
        copyInto(lockContent, sizeof lockContent, me + "\n"))
        lockRegistered.store(registration.mine = true);
    {
        std::ofstream out(mine, std::ios::trunc);
        out << me << '\n';
        if (!out.flush())
            throw InputError({caseDir.string(), 0, 0}, "case directory '" + caseDir.string() +
                                                           "' is not writable (results go there)");
    }
    std::error_code ec;
    for (int attempt = 0; attempt < 3; ++attempt) {
        if (::link(mine.c_str(), file_.c_str()) == 0) {
            owner_ = true;
            break;
        }
        const int error = errno;
        if (error != EEXIST) {
            fs::remove(mine, ec);
            throw InputError({file_.string(), 0, 0}, std::string("cannot create the case lock: ") + std::strerror(error));
        }
        std::ifstream in(file_);
        long pid = 0;
        std::string host;
        in >> pid >> host;
        if (pid == getpid() && host == hostName()) break; // this process holds it already
        const bool dead = pid > 0 && host == hostName() && ::kill(pid_t(pid), 0) != 0 && errno == ESRCH;
        if (!dead) {
            fs::remove(mine, ec);
            throw InputError({file_.string(), 0, 0},
                             "the case is in use by spindrift pid " + (pid > 0 ? std::to_string(pid) : "?") +
                                 " on host " + (host.empty() ? "?" : host) +
                                 "; wait for it to finish or stop it (remove the lock only if that process is gone)");
        }
        log::warning("stale lock " + file_.string() + " of pid " + std::to_string(pid) +
                     " (no longer running): taken over");
        fs::remove(file_, ec);
    }
    fs::remove(mine, ec);
    if (!owner_ && !fs::exists(file_, ec))
        throw InputError({file_.string(), 0, 0}, "cannot take the case lock (another solver keeps replacing it)");
}

CaseLock::~CaseLock() {
    std::error_code ec;
    if (owner_) {
        lockRegistered.store(false);
        fs::remove(file_, ec);
    }
}

void CaseLock::releaseInSignalHandler() noexcept {
    if (!lockRegistered.load()) return;
    ::unlink(lockTempPath);
    const int fd = ::open(lockPath, O_RDONLY);
    if (fd < 0) return;
    char text[sizeof lockContent];
    const ssize_t n = ::read(fd, text, sizeof text);
    ::close(fd);
    const std::size_t length = std::strlen(lockContent);
    if (n == ssize_t(length) && std::memcmp(text, lockContent, length) == 0) ::unlink(lockPath);
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
            if (isTimeName(name) || name == "postProcessing" || name == "previousRun" || name == "run") continue;
        } else {
            const std::string ext = entry.path().extension().string();
            if (name.rfind("log.", 0) == 0 || ext == ".pvd" || ext == ".png" || ext == ".tmp") continue;
        }
        fs::copy(entry.path(), target / name, fs::copy_options::recursive);
    }
}

} // namespace spindrift
