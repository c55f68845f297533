#include "io/ResourceUsage.h"

#include <sys/resource.h>

namespace jawmesh {

std::uint64_t peakResidentMemoryBytes() {
    struct rusage usage {};
    if (::getrusage(RUSAGE_SELF, &usage) != 0) return 0;
    return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024u;  // Linux reports KiB
}

}  // namespace jawmesh
