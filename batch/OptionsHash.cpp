// Implements batch/OptionsHash.h; what it computes, its rules and its contract are documented there.
#include "batch/OptionsHash.h"

#include "batch/Checksum.h"

namespace jawmesh {

std::string optionsHash(const nlohmann::json& options, const std::string& jawmeshVersion) {
    return checksumHex("jawmesh " + jawmeshVersion + "\n" + options.dump());
}

}  // namespace jawmesh
