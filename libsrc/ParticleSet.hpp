// Spindrift — particles as a structure of arrays.
//
// Every set has position, velocity, acceleration, density, pressure and id. Models register
// further fields on demand (addScalar/addVector), so a scene allocates only what its models
// use. Fields are reordered together (permute) when particles are re-sorted along the
// space-filling curve. A field flagged 'output' is written to the VTK files, 'restart' means it
// must be written (full precision) for a restart to continue bit for bit, 'scratch' that it is
// a model's working data, re-sorted but never written or snapshot.
#pragma once

#include "Types.hpp"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace spindrift {

// Reorders v as particles are re-sorted: element i becomes v[order[i]] (in parallel).
template <class T> void permuteVector(std::vector<T>& v, const std::vector<Index>& order) {
    std::vector<T> out(order.size());
    const std::size_t n = order.size();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) out[i] = v[order[i]];
    v.swap(out);
}

struct FieldOptions {
    bool output = true;   // written to the set's .vtp file
    bool restart = false; // needed to restart (written even when not selected for output)
    bool scratch = false; // a model's per-particle working data: re-sorted with the particles,
                          // never written, not kept in the last-good-state snapshot
    bool undefined = false; // the set has no value of its own (a wall's pressure and density when
                            // the boundary model mirrors the fluid's): never written, not even
                            // when named in writeFields, so that no viewer shows a false 0
};

struct ScalarField {
    std::string name;
    FieldOptions options;
    std::vector<Scalar> data;
};

struct VectorField {
    std::string name;
    FieldOptions options;
    std::vector<Vec3> data;
};

class ParticleSet {
public:
    explicit ParticleSet(std::string name = "fluid");

    const std::string& name() const { return name_; }
    std::size_t size() const { return id_.size(); }
    void resize(std::size_t n); // every field; new entries zero

    // Always present.
    std::vector<Vec3>& position() { return *position_; }
    std::vector<Vec3>& velocity() { return *velocity_; }
    std::vector<Vec3>& acceleration() { return *acceleration_; }
    std::vector<Scalar>& density() { return *density_; }
    std::vector<Scalar>& pressure() { return *pressure_; }
    std::vector<Index>& id() { return id_; }
    const std::vector<Vec3>& position() const { return *position_; }
    const std::vector<Vec3>& velocity() const { return *velocity_; }
    const std::vector<Vec3>& acceleration() const { return *acceleration_; }
    const std::vector<Scalar>& density() const { return *density_; }
    const std::vector<Scalar>& pressure() const { return *pressure_; }
    const std::vector<Index>& id() const { return id_; }

    // Mass of one particle (uniform within a set; ρ0·Δx^d for fluid).
    Scalar particleMass() const { return particleMass_; }
    void setParticleMass(Scalar m) { particleMass_ = m; }

    // Registers a field (or returns the existing one of that name; options are OR-ed).
    // The returned reference stays valid for the life of the set.
    std::vector<Scalar>& addScalar(const std::string& name, FieldOptions options = {});
    std::vector<Vec3>& addVector(const std::string& name, FieldOptions options = {});
    std::vector<Scalar>* findScalar(const std::string& name);
    std::vector<Vec3>* findVector(const std::string& name);
    const std::vector<Scalar>* findScalar(const std::string& name) const;
    const std::vector<Vec3>* findVector(const std::string& name) const;
    bool hasField(const std::string& name) const;
    // Flags an existing field as having no value of its own in this set (FieldOptions::undefined).
    void setUndefined(const std::string& name);

    const std::vector<std::unique_ptr<ScalarField>>& scalarFields() const { return scalars_; }
    const std::vector<std::unique_ptr<VectorField>>& vectorFields() const { return vectors_; }

    // Copies every field's data but the scratch fields from 'other' (a snapshot of this set
    // taken earlier, or the set to snapshot); reuses the allocated storage.
    void copyDataFrom(const ParticleSet& other);

    // Reorders every field: new[i] = old[order[i]].
    void permute(const std::vector<Index>& order);
    // Appends one particle (all fields zero except position, velocity and id).
    void append(const Vec3& position, const Vec3& velocity, Index id);

private:
    std::string name_;
    Scalar particleMass_ = 0;
    std::vector<Index> id_;
    std::vector<std::unique_ptr<ScalarField>> scalars_;
    std::vector<std::unique_ptr<VectorField>> vectors_;
    std::vector<Vec3>* position_;
    std::vector<Vec3>* velocity_;
    std::vector<Vec3>* acceleration_;
    std::vector<Scalar>* density_;
    std::vector<Scalar>* pressure_;
};

} // namespace spindrift
