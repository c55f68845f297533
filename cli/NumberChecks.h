// Command-line checks for numbers with messages a user reads in one go ("must be > 0, not -1"),
// where CLI11's own print the range of a double to 300 digits.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace jawmesh {

/// A number > 0 (help shows POSITIVE).
CLI::Validator positiveNumber();

/// A number >= 0 (help shows NONNEGATIVE).
CLI::Validator nonNegativeNumber();

}  // namespace jawmesh
