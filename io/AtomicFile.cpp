// Implements io/AtomicFile.h; what it computes, its rules and its contract are documented there.
#include "io/AtomicFile.h"

#include "io/Error.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace jawmesh {
namespace fs = std::filesystem;

namespace {
std::string temporaryName(const std::string& path) {
    return path + ".tmp-" + std::to_string(static_cast<long>(::getpid()));
}

void createParent(const std::string& path) {
    const fs::path parent = fs::path(path).parent_path();
    std::error_code ec;
    if (!parent.empty()) fs::create_directories(parent, ec);
    if (ec) throw Error(path, "cannot create folder " + parent.string() + ": " + ec.message());
}

void commit(const std::string& tmp, const std::string& path) {
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw Error(path, "cannot rename temporary file into place: " + ec.message());
    }
}
}  // namespace

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write, bool binary) {
    createParent(path);
    const std::string tmp = temporaryName(path);
    try {
        std::ofstream out(tmp, binary ? std::ios::binary | std::ios::trunc : std::ios::trunc);
        if (!out) throw Error(path, "cannot open for writing");
        write(out);
        out.flush();
        if (!out) throw Error(path, "write failed (disk full?)");
        out.close();
    } catch (...) {
        std::error_code ec;
        fs::remove(tmp, ec);
        throw;
    }
    commit(tmp, path);
}

void writeFileAtomicallyByName(const std::string& path, const std::function<void(const std::string&)>& write) {
    createParent(path);
    const std::string tmp = temporaryName(path);
    try {
        write(tmp);
    } catch (...) {
        std::error_code ec;
        fs::remove(tmp, ec);
        throw;
    }
    commit(tmp, path);
}

}  // namespace jawmesh
