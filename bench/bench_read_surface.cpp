// Times readSurface on one file: prints the median of N runs and the triangle count.
#include "io/MeshIO.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: bench_read_surface <surface> [runs]\n");
        return 2;
    }
    const int runs = argc > 2 ? std::max(1, std::stoi(argv[2])) : 5;
    std::vector<double> seconds;
    std::size_t triangles = 0;
    for (int i = 0; i < runs; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        triangles = jawmesh::readSurface(argv[1]).triangles.size();
        seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    std::sort(seconds.begin(), seconds.end());
    std::printf("| read %s | %zu triangles | median %.3f s of %d (min %.3f, max %.3f) |\n", argv[1], triangles,
                seconds[seconds.size() / 2], runs, seconds.front(), seconds.back());
    return 0;
}
