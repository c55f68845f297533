// Implements io/NumberText.h; what it computes, its rules and its contract are documented there.
#include "io/NumberText.h"

#include <charconv>

namespace jawmesh {
namespace {

/// Writes v into buf (large enough for any double in either form); returns the end.
char* toChars(char* buf, char* end, double v, int significantDigits) {
    const auto res = significantDigits > 0 ? std::to_chars(buf, end, v, std::chars_format::general, significantDigits)
                                           : std::to_chars(buf, end, v);
    return res.ptr;
}

}  // namespace

std::string numberText(double v, int significantDigits) {
    char buf[64];
    return std::string(buf, toChars(buf, buf + sizeof buf, v, significantDigits));
}

void writeNumber(std::ostream& out, double v, int significantDigits) {
    char buf[64];
    out.write(buf, toChars(buf, buf + sizeof buf, v, significantDigits) - buf);
}

}  // namespace jawmesh
