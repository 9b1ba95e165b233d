#include "Reactions.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace spindrift {

const char* forceKindName(ForceKind kind) {
    switch (kind) {
    case ForceKind::pressure: return "pressure";
    case ForceKind::viscous: return "viscous";
    case ForceKind::other: return "other";
    }
    return "?";
}

void Reactions::want(std::size_t system) {
    if (wanted(system)) return;
    systems_.push_back(system);
    sums_.emplace_back();
}

bool Reactions::wanted(std::size_t system) const {
    return std::find(systems_.begin(), systems_.end(), system) != systems_.end();
}

bool Reactions::anyWanted() const { return !systems_.empty(); }

void Reactions::clear() {
    for (auto& kinds : sums_) kinds.fill(Wrench{});
}

std::size_t Reactions::slot(std::size_t system) const {
    const auto it = std::find(systems_.begin(), systems_.end(), system);
    if (it == systems_.end()) throw std::logic_error("Reactions: system " + std::to_string(system) + " was not asked for");
    return std::size_t(it - systems_.begin());
}

void Reactions::add(std::size_t system, ForceKind kind, const Wrench& w) {
    sums_[slot(system)][std::size_t(kind)] += w;
}

const Wrench& Reactions::of(std::size_t system, ForceKind kind) const { return sums_[slot(system)][std::size_t(kind)]; }

Wrench Reactions::total(std::size_t system) const {
    Wrench t;
    for (const Wrench& w : sums_[slot(system)]) t += w;
    return t;
}

} // namespace spindrift
