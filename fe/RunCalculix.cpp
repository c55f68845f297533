// Implements fe/RunCalculix.h; what it computes, its rules and its contract are documented there.
#include "fe/RunCalculix.h"

#include "fe/CalculixResults.h"
#include "fe/CalculixWriter.h"
#include "io/Error.h"
#include "io/Labels.h"
#include "io/ResourceUsage.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sys/wait.h>

namespace fs = std::filesystem;

namespace jawmesh {
namespace {

std::string shellQuote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

std::string upper(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
    return s;
}

double percentile(std::vector<double> v, double q) {
    if (v.empty()) return 0;
    const auto k = static_cast<std::size_t>(std::min<double>(static_cast<double>(v.size() - 1), q * static_cast<double>(v.size() - 1) + 0.5));
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return v[k];
}

}  // namespace

std::string findCalculix() {
    const char* path = std::getenv("PATH");
    std::string dirs = path ? path : "/usr/bin:/bin";
    std::size_t start = 0;
    while (start <= dirs.size()) {
        const std::size_t end = std::min(dirs.find(':', start), dirs.size());
        const fs::path candidate = fs::path(dirs.substr(start, end - start)) / "ccx";
        std::error_code ec;
        if (!candidate.parent_path().empty() && fs::is_regular_file(candidate, ec)) return candidate.string();
        start = end + 1;
    }
    return "";
}

CalculixRun runCalculix(const std::string& inpPath, int threads) {
    if (!fs::is_regular_file(inpPath)) throw Error(inpPath, "CalculiX deck not found");
    CalculixRun run;
    const std::string ccx = findCalculix();
    if (ccx.empty()) {
        run.status = "not installed";
        run.message = "ccx not found on PATH (Debian package calculix-ccx)";
        return run;
    }
    const fs::path deck = fs::absolute(inpPath);
    const std::string job = deck.stem().string();
    run.logPath = (deck.parent_path() / (job + ".log")).string();
    // Old results must not pass for new ones.
    for (const char* ext : {".dat", ".frd", ".sta", ".cvg"}) fs::remove(deck.parent_path() / (job + ext));
    const std::string command = "cd " + shellQuote(deck.parent_path().string()) + " && OMP_NUM_THREADS=" +
                                std::to_string(std::max(1, threads)) + " " + shellQuote(ccx) + " -i " +
                                shellQuote(job) + " > " + shellQuote(job + ".log") + " 2>&1";
    const auto start = std::chrono::steady_clock::now();
    const int raw = std::system(command.c_str());
    run.seconds = secondsSince(start);
    run.exitCode = raw == -1 ? -1 : WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);

    bool finished = false;
    std::ifstream log(run.logPath);
    for (std::string line; std::getline(log, line);) {
        if (line.find("Job finished") != std::string::npos) finished = true;
        if (run.message.empty() && line.find("*ERROR") != std::string::npos) run.message = line;
    }
    double finalTime = 0;
    try {
        finalTime = readCalculixDat((deck.parent_path() / (job + ".dat")).string()).finalTime;
    } catch (const Error& e) {
        if (run.message.empty()) run.message = e.what();
    }
    const bool complete = run.exitCode == 0 && finished && finalTime > 1.0 - 1e-6;
    run.status = complete ? "completed" : "failed";
    if (!complete && run.message.empty())
        run.message = "ccx stopped at step time " + std::to_string(finalTime) + " (exit code " + std::to_string(run.exitCode) + ")";
    return run;
}

nlohmann::json calculixSummary(const FeScenario& scenario, const CalculixRun& run, const std::string& inpPath,
                               const TetMesh* mesh) {
    nlohmann::json j = {{"solver", "calculix"}, {"scenario", scenario.name}, {"status", run.status},
                        {"seconds", run.seconds}, {"message", run.message}};
    if (run.status != "completed") return j;
    const fs::path deck(inpPath);
    const std::string base = (deck.parent_path() / deck.stem()).string();
    const CalculixDat dat = readCalculixDat(base + ".dat");
    const auto frd = readCalculixFrdDisplacements(base + ".frd");

    // Per tooth, its largest displacement over its corner nodes (node numbers = index + 1 in the
    // deck), absolute and relative to its socket: the mean displacement of the nodes its PDL shares
    // with the bone (an implant's: the nodes it shares with the bone). The relative one is how far
    // the tooth moves in its bone (what the PDL allows);
    // the absolute one adds whatever the bone itself bends under the load.
    std::map<int, double> toothMax, toothInSocketMax;
    std::map<int, Vec3> socketMean;
    if (mesh) {
        std::vector<char> onBone(mesh->nodes.size(), 0);
        for (std::size_t t = 0; t < mesh->tets.size(); ++t)
            if (labelKind(mesh->labels[t]) == LabelKind::Bone)
                for (std::int32_t v : mesh->tets[t]) onBone[std::size_t(v)] = 1;
        std::map<int, std::set<std::int32_t>> socketNodes;
        for (std::size_t t = 0; t < mesh->tets.size(); ++t)
            if (labelKind(mesh->labels[t]) == LabelKind::Pdl || labelKind(mesh->labels[t]) == LabelKind::Implant)
                for (std::int32_t v : mesh->tets[t])
                    if (onBone[std::size_t(v)] && frd.count(v + 1)) socketNodes[labelUnn(mesh->labels[t])].insert(v);
        for (const auto& [unn, nodes] : socketNodes) {
            Vec3 sum = Vec3::Zero();
            for (std::int32_t v : nodes) sum += frd.at(v + 1);
            socketMean[unn] = sum / double(nodes.size());
        }
        for (std::size_t t = 0; t < mesh->tets.size(); ++t) {
            if (!isToothLike(labelKind(mesh->labels[t]))) continue;
            const int unn = labelUnn(mesh->labels[t]);
            double& m = toothMax[unn];
            const auto mean = socketMean.find(unn);
            double* inSocket = mean == socketMean.end() ? nullptr : &toothInSocketMax[unn];
            for (std::int32_t v : mesh->tets[t]) {
                const auto u = frd.find(v + 1);
                if (u == frd.end()) continue;
                m = std::max(m, u->second.norm());
                if (inSocket) *inSocket = std::max(*inSocket, (u->second - mean->second).norm());
            }
        }
    }
    nlohmann::json teeth = nlohmann::json::array();
    const auto printed = dat.displacements.find(upper(kCalculixLoadPointsSet));
    for (const SurfaceLoad& l : scenario.loads) {
        if (l.unn <= 0 || l.referenceNode < 0) continue;
        if (printed == dat.displacements.end() || !printed->second.count(l.referenceNode + 1))
            throw Error(base + ".dat", "no displacement printed for the load point of tooth " + std::to_string(l.unn));
        const Vec3 u = printed->second.at(l.referenceNode + 1);
        nlohmann::json tooth = {{"unn", l.unn},
                                {"load_node", l.referenceNode + 1},
                                {"displacement_mm", {u.x(), u.y(), u.z()}},
                                {"magnitude_mm", u.norm()},
                                {"along_force_mm", u.dot(l.totalForceN.normalized())}};
        if (toothMax.count(l.unn)) tooth["tooth_max_displacement_mm"] = toothMax.at(l.unn);
        if (toothInSocketMax.count(l.unn)) {
            const Vec3& m = socketMean.at(l.unn);
            tooth["socket_mean_displacement_mm"] = {m.x(), m.y(), m.z()};
            tooth["tooth_max_displacement_in_socket_mm"] = toothInSocketMax.at(l.unn);
        }
        teeth.push_back(tooth);
    }
    j["teeth"] = teeth;
    auto stats = [](const std::vector<double>& v) {
        return nlohmann::json{{"elements", v.size()},
                              {"max_von_mises_mpa", v.empty() ? 0.0 : *std::max_element(v.begin(), v.end())},
                              {"median_von_mises_mpa", percentile(v, 0.5)},
                              {"p9999_von_mises_mpa", percentile(v, 0.9999)}};
    };
    nlohmann::json regions = nlohmann::json::object();
    std::vector<double> pdl;
    for (const auto& [set, values] : dat.elementVonMisesMpa) {
        std::vector<double> v;
        for (const auto& [element, s] : values) v.push_back(s);
        std::string name = set;
        std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        regions[name] = stats(v);
        if (name.rfind("pdl_", 0) == 0) pdl.insert(pdl.end(), v.begin(), v.end());
    }
    j["regions"] = regions;
    if (!pdl.empty()) {
        // A stress spike shows as a high percentile far above the median (issue #7: under 20x).
        j["pdl"] = stats(pdl);
        const double median = percentile(pdl, 0.5);
        j["pdl"]["p9999_over_median"] = median > 0 ? percentile(pdl, 0.9999) / median : 0.0;
    }
    double maxU = 0;
    for (const auto& [node, u] : frd) maxU = std::max(maxU, u.norm());
    j["max_displacement_mm"] = maxU;
    return j;
}

}  // namespace jawmesh
