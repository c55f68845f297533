#include "batch/OptionsHash.h"

#include "batch/Checksum.h"

namespace jawmesh {

std::string optionsHash(const nlohmann::json& options, const std::string& jawmeshVersion) {
    return checksumHex("jawmesh " + jawmeshVersion + "\n" + options.dump());
}

}  // namespace jawmesh
