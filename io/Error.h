// Errors are exceptions that carry the file (when there is one) and a reason a person can act on.
// The CLI turns them into one line on stderr and a non-zero exit code; library code never exits.
#pragma once

#include <stdexcept>
#include <string>

namespace jawmesh {

/// A problem with user input or a failed stage. what() is "<file>: <reason>" when a file is known.
class Error : public std::runtime_error {
public:
    explicit Error(const std::string& reason) : std::runtime_error(reason), reason_(reason) {}
    Error(const std::string& file, const std::string& reason)
        : std::runtime_error(file + ": " + reason), file_(file), reason_(reason) {}
    const std::string& file() const { return file_; }
    const std::string& reason() const { return reason_; }

private:
    std::string file_;
    std::string reason_;
};

/// Thrown when a Progress reports cancellation (e.g. Ctrl-C); outputs are not written.
class Cancelled : public std::runtime_error {
public:
    Cancelled() : std::runtime_error("cancelled by the user") {}
};

}  // namespace jawmesh
