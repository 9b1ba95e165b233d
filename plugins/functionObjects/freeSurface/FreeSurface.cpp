// freeSurface — the fluid's free surface as a mesh, written at every written time as a block of
// its own, <name>.vtp in the time directory (listed in the .pvd beside the particle systems):
// in 3D a closed triangle mesh, in 2D closed contour lines (polylines in the plane z = 0).
//
// The surface is the iso-surface of the SPH kernel sum over every fluid system
//     φ(x) = Σ_j (m_j/ρ_j) W(|x − x_j|)      (≈ 1 inside the fluid, ½ at a flat free surface:
//                                             the level waterLevel finds along its lines)
// φ is interpolated onto a uniform grid of spacing cellSize·Δx by VTK's vtkSPHInterpolator (its
// Shepard sum; Price 2012, eq. 49), with VTK's Wendland C2 kernel (vtkWendlandQuinticKernel) of
// support kernelRadius·Δx; the grid reaches a support and a cell beyond the outermost particles,
// so φ = 0 on its border and the contour closes. φ = isoValue is contoured by flying edges
// (vtkFlyingEdges3D, vtkFlyingEdges2D; Schroeder, Maynard & Geveci 2015). A particle alone
// (spray) has φ < ½ at its centre and is not meshed.
//
//   surface { type freeSurface; cellSize 1; isoValue 0.5; kernelRadius 2; }
//
// Options: cellSize (grid spacing in particle spacings, 1; 0.5 gives a finer mesh at about 7 times
// the cost), isoValue (0.5, in (0, 1)), kernelRadius (2 particle spacings, at least 1).
// Nothing is computed between written times; the grid exists while a time is written.
#include "CaseWriter.hpp"
#include "Dictionary.hpp"
#include "Error.hpp"
#include "FunctionObject.hpp"
#include "Plugin.hpp"

#include <vtkDoubleArray.h>
#include <vtkFlyingEdges2D.h>
#include <vtkFlyingEdges3D.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>
#include <vtkSPHInterpolator.h>
#include <vtkWendlandQuinticKernel.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace {
using namespace spindrift;

// The entry's number (or its default) if 'valid' holds for it, else an InputError naming it.
template <class Valid>
double option(const Dictionary& d, const std::string& keyword, double defaultValue, Valid valid, const std::string& rule) {
    const double value = d.getOrDefault<double>(keyword, defaultValue);
    if (!valid(value)) throw InputError(d.locationOf(keyword), keyword + " must be " + rule, keyword);
    return value;
}

class FreeSurface final : public FunctionObject {
public:
    explicit FreeSurface(const ModelContext& c)
        : name_(c.name), dim_(c.physics.dimension), dx_(c.physics.particleSpacing),
          cellSize_(option(c.dict, "cellSize", 1.0, [](double v) { return v > 0 && std::isfinite(v); },
                           "positive (particle spacings)")),
          isoValue_(option(c.dict, "isoValue", 0.5, [](double v) { return v > 0 && v < 1; },
                           "between 0 and 1 (the kernel sum is 1 inside the fluid)")),
          kernelRadius_(option(c.dict, "kernelRadius", 2.0, [](double v) { return v >= 1 && std::isfinite(v); },
                               "at least 1 (particle spacings)")) {}

    std::string blockName() const override { return name_; }
    void execute(const Scene&, bool) override {} // the work is writeBlock's, at written times

    void writeBlock(const Scene& s, const std::filesystem::path& file) override {
        vtkNew<vtkPolyData> surface;
        mesh(s, *surface);
        writePolyData(file, *surface, true);
    }

private:
    // The surface of the scene's fluid into 'out' (empty without fluid particles).
    void mesh(const Scene& s, vtkPolyData& out) const {
        // the particles: positions, mass and density (their volume m/ρ weighs the kernel)
        vtkNew<vtkPoints> points;
        points->SetDataTypeToDouble();
        vtkNew<vtkDoubleArray> mass, density;
        mass->SetName("mass");
        density->SetName("density");
        double lo[3] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), 0};
        double hi[3] = {-lo[0], -lo[1], 0};
        for (const ParticleSystem* f : s.ofRole(SystemRole::fluid)) {
            const auto& x = f->particles.position();
            const auto& rho = f->particles.density();
            const double m = f->particles.particleMass();
            for (std::size_t i = 0; i < f->ownedSize(); ++i) {
                const double p[3] = {double(x[i][0]), double(x[i][1]), dim_ == 3 ? double(x[i][2]) : 0.0};
                points->InsertNextPoint(p);
                mass->InsertNextValue(m);
                density->InsertNextValue(double(rho[i]));
                for (int k = 0; k < dim_; ++k) {
                    lo[k] = std::min(lo[k], p[k]);
                    hi[k] = std::max(hi[k], p[k]);
                }
            }
        }
        if (points->GetNumberOfPoints() == 0) { // an empty mesh, with the (empty) points readers expect
            vtkNew<vtkPoints> none;
            out.SetPoints(none);
            return;
        }
        vtkNew<vtkPolyData> particles;
        particles->SetPoints(points);
        particles->GetPointData()->AddArray(mass);
        particles->GetPointData()->AddArray(density);

        // the grid: a support and a cell beyond the particles on every side (φ = 0 on its border)
        const double cell = cellSize_ * dx_, pad = kernelRadius_ * dx_ + cell;
        int n[3] = {1, 1, 1};
        double origin[3] = {0, 0, 0};
        double gridPoints = 1;
        for (int k = 0; k < dim_; ++k) {
            origin[k] = lo[k] - pad;
            const double cells = std::ceil((hi[k] - lo[k] + 2 * pad) / cell);
            gridPoints *= cells + 1;
            n[k] = int(std::min(cells + 1, double(std::numeric_limits<int>::max())));
        }
        if (gridPoints > maxGridPoints)
            throw std::runtime_error("freeSurface '" + name_ + "': the fluid's bounding box needs a grid of " +
                                     std::to_string(gridPoints) + " points at cellSize " + std::to_string(cellSize_) +
                                     " (a particle far from the others?); raise cellSize");
        vtkNew<vtkImageData> grid;
        grid->SetDimensions(n);
        grid->SetOrigin(origin);
        grid->SetSpacing(cell, cell, cell);

        vtkNew<vtkWendlandQuinticKernel> kernel;
        kernel->SetDimension(dim_);
        kernel->SetSpatialStep(kernelRadius_ * dx_ / kernel->GetCutoffFactor());
        vtkNew<vtkSPHInterpolator> phi;
        phi->SetInputData(grid);
        phi->SetSourceData(particles);
        phi->SetKernel(kernel);
        phi->SetMassArrayName("mass");
        phi->SetDensityArrayName("density");
        phi->AddExcludedArray("mass");
        phi->AddExcludedArray("density");
        phi->ComputeShepardSumOn();
        phi->SetShepardSumArrayName("phi");
        phi->SetNullPointsStrategyToNullValue();
        phi->SetNullValue(0);
        phi->PassPointArraysOff();

        vtkSmartPointer<vtkPolyDataAlgorithm> contour;
        if (dim_ == 3) {
            auto edges = vtkSmartPointer<vtkFlyingEdges3D>::New();
            edges->ComputeNormalsOff();
            edges->ComputeGradientsOff();
            edges->ComputeScalarsOff();
            edges->SetValue(0, isoValue_);
            contour = edges;
        } else {
            auto edges = vtkSmartPointer<vtkFlyingEdges2D>::New();
            edges->ComputeScalarsOff();
            edges->SetValue(0, isoValue_);
            contour = edges;
        }
        // VTK's threads (its own pool; the solver's OpenMP threads wait at a write), as many
        // as the solver's: the same mesh at any count (each grid value is computed alone)
        vtkSMPTools::Config threads;
        threads.MaxNumberOfThreads = threadCount();
        threads.Backend = "STDThread";
        vtkSMPTools::LocalScope(threads, [&] {
            phi->Update();
            vtkDataSet* field = phi->GetOutput();
            field->GetPointData()->SetActiveScalars("phi"); // (flying edges 2D reads the active scalars' type)
            contour->SetInputData(field);
            contour->Update();
        });
        out.ShallowCopy(contour->GetOutput());
    }

    static int threadCount() {
#ifdef _OPENMP
        return omp_get_max_threads();
#else
        return 1;
#endif
    }

    static constexpr double maxGridPoints = 1e9;
    std::string name_;
    int dim_;
    double dx_, cellSize_, isoValue_, kernelRadius_;
};
} // namespace

SPINDRIFT_PLUGIN(FunctionObject, FreeSurface)
