#include "ParticleSet.hpp"

namespace spindrift {

ParticleSet::ParticleSet(std::string name) : name_(std::move(name)) {
    position_ = &addVector("position", {false, true});
    velocity_ = &addVector("velocity", {true, true});
    // acceleration is restart data: the first step after a restart needs the previous step's
    // accelerations (time-step limit, leapfrog) to continue bit for bit
    acceleration_ = &addVector("acceleration", {false, true});
    density_ = &addScalar("density", {true, true});
    pressure_ = &addScalar("pressure", {true, true});
}

void ParticleSet::resize(std::size_t n) {
    id_.resize(n, 0);
    for (auto& f : scalars_) f->data.resize(n, Scalar(0));
    for (auto& f : vectors_) f->data.resize(n, Vec3::Zero());
}

namespace {
// The field of that name, its options widened by a second request (written or restart data if
// either asks, scratch only if both do); a new field of zeros if there is none.
template <class Field, class Value>
std::vector<Value>& addField(std::vector<std::unique_ptr<Field>>& fields, const std::string& name,
                             FieldOptions options, std::size_t size, const Value& zero) {
    for (auto& f : fields)
        if (f->name == name) {
            f->options.output |= options.output;
            f->options.restart |= options.restart;
            f->options.scratch &= options.scratch;
            f->options.undefined |= options.undefined;
            return f->data;
        }
    fields.push_back(std::make_unique<Field>(Field{name, options, {}}));
    fields.back()->data.assign(size, zero);
    return fields.back()->data;
}
} // namespace

std::vector<Scalar>& ParticleSet::addScalar(const std::string& name, FieldOptions options) {
    return addField(scalars_, name, options, size(), Scalar(0));
}

std::vector<Vec3>& ParticleSet::addVector(const std::string& name, FieldOptions options) {
    return addField(vectors_, name, options, size(), Vec3(Vec3::Zero()));
}

std::vector<Scalar>* ParticleSet::findScalar(const std::string& name) {
    for (auto& f : scalars_)
        if (f->name == name) return &f->data;
    return nullptr;
}
std::vector<Vec3>* ParticleSet::findVector(const std::string& name) {
    for (auto& f : vectors_)
        if (f->name == name) return &f->data;
    return nullptr;
}
const std::vector<Scalar>* ParticleSet::findScalar(const std::string& name) const {
    return const_cast<ParticleSet*>(this)->findScalar(name);
}
const std::vector<Vec3>* ParticleSet::findVector(const std::string& name) const {
    return const_cast<ParticleSet*>(this)->findVector(name);
}
bool ParticleSet::hasField(const std::string& name) const {
    return name == "id" || findScalar(name) || findVector(name);
}

void ParticleSet::setUndefined(const std::string& name) {
    for (auto& f : scalars_)
        if (f->name == name) f->options.undefined = true;
    for (auto& f : vectors_)
        if (f->name == name) f->options.undefined = true;
}

namespace {
// Runs every step (the last-good-state snapshot): in parallel.
template <class T> void parallelCopy(std::vector<T>& to, const std::vector<T>& from) {
    to.resize(from.size());
    const std::size_t n = from.size();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) to[i] = from[i];
}
} // namespace

void ParticleSet::copyDataFrom(const ParticleSet& other) {
    particleMass_ = other.particleMass_;
    parallelCopy(id_, other.id_);
    for (const auto& f : other.scalars_)
        if (!f->options.scratch) parallelCopy(addScalar(f->name, f->options), f->data);
    for (const auto& f : other.vectors_)
        if (!f->options.scratch) parallelCopy(addVector(f->name, f->options), f->data);
    // a model's working data keeps the particle count (a system whose count changed since)
    for (auto& f : scalars_)
        if (f->options.scratch) f->data.resize(id_.size());
    for (auto& f : vectors_)
        if (f->options.scratch) f->data.resize(id_.size(), Vec3::Zero());
}

void ParticleSet::permute(const std::vector<Index>& order) {
    permuteVector(id_, order);
    for (auto& f : scalars_) permuteVector(f->data, order);
    for (auto& f : vectors_) permuteVector(f->data, order);
}

void ParticleSet::append(const Vec3& x, const Vec3& v, Index id) {
    resize(size() + 1);
    position().back() = x;
    velocity().back() = v;
    id_.back() = id;
}

} // namespace spindrift
