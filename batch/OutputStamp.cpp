// Implements batch/OutputStamp.h; what it computes, its rules and its contract are documented there.
#include "batch/OutputStamp.h"

#include "batch/Checksum.h"
#include "io/AtomicFile.h"
#include "io/Error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace jawmesh {
namespace fs = std::filesystem;

std::vector<StampedFile> stampFiles(const std::string& dir) {
    std::vector<StampedFile> files;
    std::error_code ec;
    for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        if (!it->is_regular_file()) continue;
        const std::string rel = it->path().lexically_relative(dir).generic_string();
        if (rel == kOutputStampName) continue;
        files.push_back({rel, static_cast<std::uint64_t>(it->file_size()), fileChecksumHex(it->path().string())});
    }
    if (ec) throw Error(dir, "cannot list folder: " + ec.message());
    std::sort(files.begin(), files.end(), [](const StampedFile& a, const StampedFile& b) { return a.path < b.path; });
    return files;
}

void writeOutputStamp(const OutputStamp& stamp, const std::string& dir) {
    nlohmann::json files = nlohmann::json::array();
    for (const StampedFile& f : stamp.files)
        files.push_back({{"path", f.path}, {"bytes", f.bytes}, {"checksum", f.checksum}});
    const nlohmann::json j = {{"options_hash", stamp.optionsHash},
                              {"status", "ok"},
                              {"seconds", stamp.seconds},
                              {"peak_memory_bytes", stamp.peakMemoryBytes},
                              {"files", files}};
    writeFileAtomically(dir + "/" + kOutputStampName, [&](std::ostream& out) { out << j.dump(2) << '\n'; }, false);
}

std::string outputProblem(const std::string& dir, const std::string& optionsHash,
                          const std::vector<std::string>& required, OutputStamp* stampOut) {
    const std::string stampPath = dir + "/" + kOutputStampName;
    std::ifstream in(stampPath);
    if (!in) return "no completion stamp " + stampPath;
    OutputStamp stamp;
    try {
        const nlohmann::json j = nlohmann::json::parse(in);
        if (j.at("status") != "ok") return stampPath + ": status is not ok";
        stamp.optionsHash = j.at("options_hash").get<std::string>();
        stamp.seconds = j.at("seconds").get<double>();
        stamp.peakMemoryBytes = j.at("peak_memory_bytes").get<std::uint64_t>();
        for (const nlohmann::json& f : j.at("files"))
            stamp.files.push_back({f.at("path").get<std::string>(), f.at("bytes").get<std::uint64_t>(),
                                   f.at("checksum").get<std::string>()});
    } catch (const nlohmann::json::exception& e) {
        return stampPath + ": unreadable stamp (" + e.what() + ")";
    }
    if (stamp.optionsHash != optionsHash)
        return "made with other options (hash " + stamp.optionsHash + ", now " + optionsHash + ")";
    for (const std::string& r : required)
        if (std::none_of(stamp.files.begin(), stamp.files.end(), [&](const StampedFile& f) { return f.path == r; }))
            return stampPath + ": does not list " + r;
    for (const StampedFile& f : stamp.files) {
        const std::string path = dir + "/" + f.path;
        std::error_code ec;
        const std::uintmax_t bytes = fs::file_size(path, ec);
        if (ec) return path + ": missing";
        if (bytes != f.bytes)
            return path + ": " + std::to_string(bytes) + " bytes, " + std::to_string(f.bytes) + " when completed";
        try {
            if (fileChecksumHex(path) != f.checksum) return path + ": contents changed since completion";
        } catch (const Error& e) {
            return e.what();
        }
    }
    if (stampOut) *stampOut = stamp;
    return "";
}

}  // namespace jawmesh
