#include "Scene.hpp"

#include "RigidBody.hpp"

#include <numeric>
#include <stdexcept>

namespace spindrift {

const char* roleName(SystemRole role) {
    switch (role) {
    case SystemRole::fluid: return "fluid";
    case SystemRole::wall: return "wall";
    case SystemRole::body: return "body";
    case SystemRole::passive: return "passive";
    }
    return "?";
}

ParticleSystem::ParticleSystem(std::string name, SystemRole role_, std::size_t index_)
    : particles(std::move(name)), role(role_), index(index_) {}
ParticleSystem::~ParticleSystem() = default;

ParticleSystem& Scene::addSystem(const std::string& name, SystemRole role) {
    systems.push_back(std::make_unique<ParticleSystem>(name, role, systems.size()));
    return *systems.back();
}

void Scene::registerWithSearch(const ParticleSystem& p) {
    if (search.systemCount() != p.index)
        throw std::logic_error("Scene::registerWithSearch: system '" + p.name() + "' out of order");
    search.addSystem(&p.particles.position(), !p.moves());
    for (std::size_t k = 0; k <= p.index; ++k) {
        const ParticleSystem& other = *systems[k];
        if (p.isFluid() && (other.isFluid() || other.isBoundary())) search.addInteraction(p.index, other.index);
        if (p.isBoundary() && other.isFluid()) search.addInteraction(other.index, p.index);
        if (p.isFluid() && other.isFluid() && k != p.index) search.addInteraction(other.index, p.index);
        // a body meets the walls and the other bodies (its contacts)
        if (k != p.index && p.role == SystemRole::body && other.isBoundary()) search.addInteraction(p.index, other.index);
        if (k != p.index && other.role == SystemRole::body && p.isBoundary()) search.addInteraction(other.index, p.index);
    }
}

ParticleSystem* Scene::find(const std::string& name) {
    for (auto& p : systems)
        if (p->name() == name) return p.get();
    return nullptr;
}

const ParticleSystem* Scene::find(const std::string& name) const {
    for (const auto& p : systems)
        if (p->name() == name) return p.get();
    return nullptr;
}

std::vector<ParticleSystem*> Scene::ofRole(SystemRole role) {
    std::vector<ParticleSystem*> out;
    for (auto& p : systems)
        if (p->role == role) out.push_back(p.get());
    return out;
}

std::vector<const ParticleSystem*> Scene::ofRole(SystemRole role) const {
    std::vector<const ParticleSystem*> out;
    for (const auto& p : systems)
        if (p->role == role) out.push_back(p.get());
    return out;
}

std::vector<ParticleSystem*> Scene::boundaries() {
    std::vector<ParticleSystem*> out;
    for (auto& p : systems)
        if (p->isBoundary()) out.push_back(p.get());
    return out;
}

std::vector<const ParticleSystem*> Scene::boundaries() const {
    std::vector<const ParticleSystem*> out;
    for (const auto& p : systems)
        if (p->isBoundary()) out.push_back(p.get());
    return out;
}

bool Scene::anyMovingBoundary() const {
    for (const auto& p : systems)
        if (p->movingBoundary()) return true;
    return false;
}

std::size_t Scene::particlesOf(SystemRole role) const {
    std::size_t n = 0;
    for (const auto& p : systems)
        if (p->role == role) n += p->ownedSize();
    return n;
}

void resortSystem(Scene& s, ParticleSystem& system) {
    auto& x = system.particles.position();
    // the system's own particles along the curve; its ghosts stay after them, in their order
    std::vector<Index> order = s.search.sortOrder(std::vector<Vec3>(x.begin(), x.begin() + system.ownedSize()));
    order.resize(x.size());
    std::iota(order.begin() + system.ownedSize(), order.end(), Index(system.ownedSize()));
    // lists made at exactly these positions (the last build, or one made ahead) are kept, the
    // boundaries being where they were then (the core makes the lists of the state and time)
    const bool keepSearch = s.search.listsAt(system.index, x);
    const QueryLists& q = s.search.of(system.index);
    if (keepSearch && system.gradients.validFor(q)) {
        const NeighbourList& own = q.own(); // still in the old order
        std::vector<Vec3> gradients;
        permuteRowData(own, order, permutedOffsets(own, order), system.gradients.values, gradients);
        system.gradients.values.swap(gradients);
    }
    system.particles.permute(order);
    if (keepSearch) s.search.permute(system.index, order);
    else system.gradients.invalidate();
}

} // namespace spindrift
