// A parallel loop whose error does not depend on the threads: every index runs, and what the
// lowest failing index threw is rethrown afterwards (reading the case's files, meshing the label
// volume's regions, labelling TetGen's groups).
#pragma once

#include "io/Progress.h"

#include <tbb/parallel_for.h>

#include <atomic>
#include <cstddef>
#include <exception>
#include <vector>

namespace jawmesh {

/// Calls f(i) for every i in [0, n) in parallel; when some throw, rethrows the exception of the
/// lowest such i once all have run (the others are dropped).
template <typename F>
void parallelForFirstErrorInOrder(std::size_t n, F&& f) {
    std::vector<std::exception_ptr> errors(n);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
        try {
            f(i);
        } catch (...) {
            errors[i] = std::current_exception();
        }
    });
    for (const std::exception_ptr& e : errors)
        if (e) std::rethrow_exception(e);
}

/// The same over steps of a stage of `progress`: each step first checks for cancellation, and
/// after it the share done goes to progress.update, the steps weighed by `weights` (e.g. their
/// triangles) when given, else each one alike.
template <typename F>
void parallelForFirstErrorInOrder(std::size_t n, Progress& progress, F&& f, const std::vector<std::size_t>& weights = {}) {
    std::size_t total = 0;
    for (std::size_t i = 0; i < n; ++i) total += weights.empty() ? 1 : weights[i];
    std::atomic<std::size_t> done{0};
    parallelForFirstErrorInOrder(n, [&](std::size_t i) {
        progress.checkCancelled();
        f(i);
        const std::size_t now = done += weights.empty() ? 1 : weights[i];
        progress.update(total > 0 ? double(now) / double(total) : 1.0);
    });
}

}  // namespace jawmesh
