// spindriftFluidInBox — case-test helper: checks that the fluid of a fluid.vtp written by the
// solver is still held by an open-top tank, and prints the particles' bounding box (2D, x-y).
//   spindriftFluidInBox <fluid.vtp> <xmin> <ymin> <xmax> <wallTop> <ceiling> <tolerance>
// A particle fails when it is not finite, below the floor (y < ymin − tolerance), beside the
// tank below the top of its walls (x < xmin − tolerance or x > xmax + tolerance while
// y < wallTop), or above the ceiling. Spray above the open top (wallTop <= y <= ceiling) is
// allowed anywhere. Exit 0 when no particle fails, 1 (with the count and the worst) otherwise,
// 2 on errors.
#include "CaseWriter.hpp"

#include <cmath>
#include <cstdlib>
#include <iostream>

int main(int argc, char** argv) {
    if (argc != 8) {
        std::cerr << "usage: spindriftFluidInBox <fluid.vtp> <xmin> <ymin> <xmax> <wallTop> <ceiling> <tolerance>\n";
        return 2;
    }
    try {
        const spindrift::ParticleSet set = spindrift::readVtp(argv[1]);
        const double xmin = std::atof(argv[2]), ymin = std::atof(argv[3]), xmax = std::atof(argv[4]);
        const double wallTop = std::atof(argv[5]), ceiling = std::atof(argv[6]), tol = std::atof(argv[7]);
        if (set.size() == 0) {
            std::cerr << argv[1] << ": no particles\n";
            return 1;
        }
        spindrift::Vec3 bmin = set.position()[0], bmax = bmin;
        std::size_t failed = 0, worst = 0;
        double worstDistance = 0;
        for (std::size_t i = 0; i < set.size(); ++i) {
            const spindrift::Vec3& x = set.position()[i];
            bmin = bmin.cwiseMin(x);
            bmax = bmax.cwiseMax(x);
            double d = x.allFinite() ? 0.0 : INFINITY;
            d = std::max({d, ymin - tol - x.y(), x.y() - ceiling});
            if (x.y() < wallTop) d = std::max({d, xmin - tol - x.x(), x.x() - xmax - tol});
            if (d > 0) {
                ++failed;
                if (d >= worstDistance) worstDistance = d, worst = i;
            }
        }
        std::cout << set.size() << " particles in (" << bmin.x() << " " << bmin.y() << ") - (" << bmax.x() << " "
                  << bmax.y() << ")\n";
        if (failed > 0) {
            std::cout << failed << " particles left the tank (" << xmin << " " << ymin << ") - (" << xmax << " "
                      << wallTop << "), tolerance " << tol << ", ceiling " << ceiling << "; worst: id "
                      << set.id()[worst] << " at (" << set.position()[worst].transpose() << "), " << worstDistance
                      << " m out\n";
            return 1;
        }
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "spindriftFluidInBox: " << e.what() << "\n";
        return 2;
    }
}
