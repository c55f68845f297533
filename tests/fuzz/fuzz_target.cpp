// A libFuzzer executable for the reader named by JAWMESH_FUZZ_TARGET (tests/fuzz/FuzzTargets.h).
#include "FuzzTargets.h"

#include <cstdint>
#include <cstdlib>
#include <cstring>

namespace {
const jawmesh::fuzz::Target& target() {
    for (const auto& t : jawmesh::fuzz::targets())
        if (std::strcmp(t.name, JAWMESH_FUZZ_TARGET) == 0) return t;
    std::abort();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const jawmesh::fuzz::Target& t = target();
    if (!t.run(std::string(reinterpret_cast<const char*>(data), size))) std::abort();  // an invalid result
    return 0;
}
