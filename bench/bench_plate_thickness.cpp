// Times the thin-plate measure (filters/PlateThickness.h) the simplification starts with, on the
// fine extraction of a carved label field (e.g. a run's levelsets/ folder): median of N runs, the
// vertices measured (near the teeth) and how many lie on a plate.
// Usage: bench_plate_thickness <levelsets dir> [runs]
#include "filters/ExtractInterfaces.h"
#include "filters/NearTeeth.h"
#include "filters/PlateThickness.h"
#include "filters/SimplifyInterfaces.h"
#include "levelset/LabelFieldIO.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: bench_plate_thickness <levelsets dir> [runs]\n");
        return 2;
    }
    const int runs = argc > 2 ? std::max(1, std::stoi(argv[2])) : 3;
    jawmesh::ExtractOptions fineOptions;
    fineOptions.adaptive.maxLevel = 0;  // plates are measured on the fine extraction
    const jawmesh::InterfaceComplex fine = jawmesh::extractInterfaces(jawmesh::readLabelField(argv[1]), fineOptions);
    const jawmesh::SimplifyOptions o;
    const std::vector<char> near = jawmesh::verticesNearTeeth(fine, o.boneNearTeethMm);
    std::vector<double> seconds;
    std::size_t onPlates = 0;
    for (int i = 0; i < runs; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        const std::vector<float> t = jawmesh::plateThicknessMm(fine, near, jawmesh::PlateOptions{o.plateMaxMm});
        seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        onPlates = std::size_t(std::count_if(t.begin(), t.end(), [](float x) { return std::isfinite(x); }));
    }
    std::sort(seconds.begin(), seconds.end());
    std::printf("| plate thickness, %s | %zu triangles, %zu vertices (%zu near the teeth), %zu on plates | median %.2f s of %d (min %.2f, max %.2f) |\n",
                argv[1], fine.surface.triangles.size(), fine.surface.vertices.size(),
                std::size_t(std::count(near.begin(), near.end(), char(1))), onPlates, seconds[seconds.size() / 2], runs,
                seconds.front(), seconds.back());
    return 0;
}
