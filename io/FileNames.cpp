// Implements io/FileNames.h.
#include "io/FileNames.h"

#include <algorithm>
#include <cctype>

namespace jawmesh {

bool endsWithIgnoringCase(const std::string& name, const std::string& suffix) {
    const auto lower = [](unsigned char c) { return std::tolower(c); };
    return name.size() >= suffix.size() &&
           std::equal(suffix.rbegin(), suffix.rend(), name.rbegin(),
                      [&](char a, char b) { return lower(static_cast<unsigned char>(a)) == lower(static_cast<unsigned char>(b)); });
}

}  // namespace jawmesh
