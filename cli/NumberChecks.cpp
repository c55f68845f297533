// Implements cli/NumberChecks.h; what it computes, its rules and its contract are documented there.
#include "cli/NumberChecks.h"

#include <cmath>
#include <cstdlib>

namespace jawmesh {
namespace {

/// Checks that the text is a whole number (finite, nothing after it) that `ok` accepts.
template <typename Ok>
CLI::Validator numberCheck(const std::string& name, const std::string& rule, Ok ok) {
    return CLI::Validator(
        [rule, ok](std::string& text) -> std::string {
            char* end = nullptr;
            const double value = std::strtod(text.c_str(), &end);
            if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value))
                return "must be a number, not '" + text + "'";
            return ok(value) ? std::string() : "must be " + rule + ", not " + text;
        },
        name, name);
}

}  // namespace

CLI::Validator positiveNumber() {
    return numberCheck("POSITIVE", "> 0", [](double v) { return v > 0; });
}

CLI::Validator nonNegativeNumber() {
    return numberCheck("NONNEGATIVE", ">= 0", [](double v) { return v >= 0; });
}

}  // namespace jawmesh
