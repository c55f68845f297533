// Implements io/StagedFolder.h; what it computes, its rules and its contract are documented there.
#include "io/StagedFolder.h"

#include "io/Error.h"

#include <filesystem>
#include <unistd.h>
#include <vector>

namespace jawmesh {
namespace fs = std::filesystem;

namespace {
/// The destination without a trailing separator, so that it has a file name to hide the staging under.
fs::path normalDest(const std::string& destDir) {
    fs::path p = fs::path(destDir).lexically_normal();
    if (p.has_filename()) return p;
    p = p.parent_path();
    if (p.empty() || !p.has_filename() || p.filename() == "." || p.filename() == "..")
        p = fs::absolute(destDir).lexically_normal();
    if (!p.has_filename()) p = p.parent_path();
    return p;
}
}  // namespace

StagedFolder::StagedFolder(const std::string& destDir) {
    const fs::path dest = normalDest(destDir);
    if (dest.filename().empty() || dest == dest.root_path())
        throw Error(destDir, "cannot be an output folder (no folder name)");
    dest_ = dest.string();
    fs::path parent = dest.has_parent_path() ? dest.parent_path() : fs::path(".");
    std::error_code ec;
    for (fs::path p = parent; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
        createdTop_ = p.string();
        if (p == p.parent_path()) break;
    }
    fs::create_directories(parent, ec);
    if (ec) throw Error(destDir, "cannot create folder " + parent.string() + ": " + ec.message());
    staging_ = (parent / ("." + dest.filename().string() + ".partial-" + std::to_string(static_cast<long>(::getpid()))))
                   .string();
    fs::remove_all(staging_, ec);
    fs::create_directory(staging_, ec);
    if (ec) throw Error(destDir, "cannot create staging folder " + staging_ + ": " + ec.message());
}

StagedFolder::~StagedFolder() {
    if (committed_) return;
    std::error_code ec;
    fs::remove_all(staging_, ec);
    if (createdTop_.empty()) return;
    // Only empty folders go: another process may have written into a parent meanwhile.
    const fs::path top = createdTop_;
    for (fs::path p = fs::path(staging_).parent_path(); !p.empty(); p = p.parent_path()) {
        if (!fs::remove(p, ec) || ec) break;
        if (p == top) break;
    }
}

void replaceFolder(const std::string& completeDir, const std::string& destDir) {
    std::error_code ec;
    const std::string old = completeDir + ".old";
    const bool hadOld = fs::exists(destDir, ec);
    if (hadOld) {
        fs::remove_all(old, ec);
        fs::rename(destDir, old, ec);
        if (ec) throw Error(destDir, "cannot move the previous outputs aside: " + ec.message());
    }
    fs::rename(completeDir, destDir, ec);
    if (ec) throw Error(destDir, "cannot rename the completed outputs into place: " + ec.message());
    if (hadOld) fs::remove_all(old, ec);
}

void StagedFolder::commit(Mode mode) {
    std::error_code ec;
    if (mode == Mode::Replace || !fs::exists(dest_, ec)) {
        replaceFolder(staging_, dest_);
        committed_ = true;
        return;
    }
    if (!fs::is_directory(dest_, ec)) throw Error(dest_, "exists and is not a folder");
    std::vector<fs::path> files;
    for (fs::recursive_directory_iterator it(staging_, ec), end; !ec && it != end; it.increment(ec))
        if (!it->is_directory()) files.push_back(it->path());
    if (ec) throw Error(staging_, "cannot list staged outputs: " + ec.message());
    for (const fs::path& from : files) {
        const fs::path to = fs::path(dest_) / from.lexically_relative(staging_);
        fs::create_directories(to.parent_path(), ec);
        if (!ec) fs::rename(from, to, ec);
        if (ec) throw Error(to.string(), "cannot move the completed output into place: " + ec.message());
    }
    committed_ = true;
    fs::remove_all(staging_, ec);
}

}  // namespace jawmesh
