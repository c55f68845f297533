// Implements levelset/LeastAreaLoop.h; what it computes, its rules and its contract are documented there.
#include "levelset/LeastAreaLoop.h"

#include <Eigen/Geometry>

#include <limits>

namespace jawmesh {

std::vector<Tri> minimumAreaLoop(const std::vector<Vec3>& loop, const std::function<bool(int, int)>& diagonalAllowed) {
    const int n = int(loop.size());
    if (n < 3) return {};
    constexpr double kNone = std::numeric_limits<double>::infinity();
    // area[i][j]: least area of the sub-polygon i, i+1, ..., j closed by the chord j-i;
    // apex[i][j]: the vertex its triangle on that chord uses.
    std::vector<double> area(std::size_t(n * n), kNone);
    std::vector<int> apex(std::size_t(n * n), -1);
    const auto at = [n](int i, int j) { return std::size_t(i * n + j); };
    for (int i = 0; i + 1 < n; ++i) area[at(i, i + 1)] = 0;
    for (int span = 2; span < n; ++span)
        for (int i = 0; i + span < n; ++i) {
            const int j = i + span;
            // chord i-j is a loop edge only for the whole polygon (i = 0, j = n - 1)
            if (!(i == 0 && j == n - 1) && !diagonalAllowed(i, j)) continue;
            for (int k = i + 1; k < j; ++k) {
                const double sub = area[at(i, k)] + area[at(k, j)];
                if (!(sub < kNone)) continue;
                const double a = sub + 0.5 * (loop[std::size_t(k)] - loop[std::size_t(i)]).cross(loop[std::size_t(j)] - loop[std::size_t(i)]).norm();
                if (a < area[at(i, j)]) {
                    area[at(i, j)] = a;
                    apex[at(i, j)] = k;
                }
            }
        }
    if (apex[at(0, n - 1)] < 0) return {};
    std::vector<Tri> tris;
    std::vector<std::pair<int, int>> todo = {{0, n - 1}};
    while (!todo.empty()) {
        const auto [i, j] = todo.back();
        todo.pop_back();
        if (j - i < 2) continue;
        const int k = apex[at(i, j)];
        tris.push_back({i, k, j});  // wound as the loop: i -> k -> j
        todo.push_back({i, k});
        todo.push_back({k, j});
    }
    return tris;
}

}  // namespace jawmesh
