// The identity of a batch's settings: outputs made with the same hash are interchangeable, so a
// rerun may keep them; any change of an option or of the jawmesh version invalidates them.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace jawmesh {

/// checksumHex of "jawmesh <version>\n" + options.dump() (nlohmann's dump sorts keys, so the hash
/// does not depend on the order the options were given in).
std::string optionsHash(const nlohmann::json& options, const std::string& jawmeshVersion);

}  // namespace jawmesh
