// A parallel loop whose error does not depend on the threads: every index runs, and what the
// lowest failing index threw is rethrown afterwards (reading the case's files, meshing the label
// volume's regions, labelling TetGen's groups).
#pragma once

#include <tbb/parallel_for.h>

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

}  // namespace jawmesh
