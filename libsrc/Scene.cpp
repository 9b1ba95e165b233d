#include "Scene.hpp"

namespace spindrift {

void resortFluid(Scene& s) {
    const std::vector<Index> order = s.search.sortOrder(s.fluid.position());
    const bool keepSearch = s.search.listsAt(s.fluid.position());
    if (keepSearch && s.gradients.validFor(s.search)) {
        const NeighbourList& ff = s.search.fluidNeighbours(); // still in the old order
        std::vector<Vec3> gradients;
        permuteRowData(ff, order, permutedOffsets(ff, order), s.gradients.values, gradients);
        s.gradients.values.swap(gradients);
    }
    s.fluid.permute(order);
    if (keepSearch) s.search.permute(order);
    else s.gradients.invalidate();
}

} // namespace spindrift
