#include "io/Case.h"

#include "io/Angles.h"
#include "io/Error.h"
#include "io/MeshIO.h"

#include <Eigen/Eigenvalues>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <filesystem>
#include <numeric>
#include <sstream>

namespace jawmesh {
namespace fs = std::filesystem;

namespace {

std::vector<fs::path> sortedEntries(const fs::path& dir) {
    std::vector<fs::path> entries;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) entries.push_back(it->path());
    if (ec) throw Error(dir.string(), "cannot list folder: " + ec.message());
    std::sort(entries.begin(), entries.end());
    return entries;
}

bool isDir(const fs::path& p) {
    std::error_code ec;
    return fs::is_directory(p, ec);
}

bool isFile(const fs::path& p) {
    std::error_code ec;
    return fs::is_regular_file(p, ec);
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

std::string stemOf(const fs::path& p) { return p.stem().string(); }

bool isAllTeethObj(const fs::path& p) { return isFile(p) && lower(p.filename().string()) == "all_teeth.obj"; }

JawCase discoverJaw(const fs::path& jawDir, Jaw jaw) {
    const std::string name = jawName(jaw);
    JawCase jc;
    jc.jaw = jaw;

    const fs::path boneDir = jawDir / "bone";
    std::vector<std::string> bones;
    if (isDir(boneDir))
        for (const fs::path& p : sortedEntries(boneDir))
            if (isFile(p) && lower(stemOf(p)) == name && isSurfaceExtension(surfaceExtension(p.string())))
                bones.push_back(p.string());
    if (bones.empty())
        throw Error(jawDir.string(), "no bone surface: expected bone/" + name + ".stl (or .obj, .ply, .off)");
    if (bones.size() > 1) throw Error(boneDir.string(), "several bone surfaces (" + bones[0] + ", " + bones[1] + "); keep one");
    jc.bonePath = bones[0];

    const fs::path teethDir = jawDir / "teeth";
    std::vector<std::string> allTeeth;
    if (isAllTeethObj(jawDir / "all_teeth.obj")) allTeeth.push_back((jawDir / "all_teeth.obj").string());
    if (isDir(teethDir)) {
        for (const fs::path& p : sortedEntries(teethDir)) {
            if (!isFile(p) || !isSurfaceExtension(surfaceExtension(p.string()))) continue;
            if (isAllTeethObj(p)) {
                allTeeth.push_back(p.string());
                continue;
            }
            const std::string stem = lower(stemOf(p));
            const std::string digits = stem.size() > 6 && stem.compare(0, 6, "tooth_") == 0 ? stem.substr(6) : "";
            if (digits.empty() || digits.size() > 3 || digits.find_first_not_of("0123456789") != std::string::npos)
                throw Error(p.string(), "cannot read a tooth number from this file name: expected tooth_<UNN>." +
                                            surfaceExtension(p.string()) + " (UNN 1..32) or all_teeth.obj");
            const int unn = std::stoi(digits);
            if (!isValidUnn(unn)) throw Error(p.string(), "tooth number " + std::to_string(unn) + " is outside 1..32");
            if (jawOfTooth(unn) != jaw)
                throw Error(p.string(), "tooth " + std::to_string(unn) + " belongs to the " + jawName(jawOfTooth(unn)) +
                                            " (" + (jaw == Jaw::Mandible ? "1..16" : "17..32") + "), not the " + name +
                                            " (" + (jaw == Jaw::Mandible ? "17..32" : "1..16") + ")");
            const auto [it, inserted] = jc.toothPaths.emplace(unn, p.string());
            if (!inserted)
                throw Error(p.string(), "tooth " + std::to_string(unn) + " is given twice (also " + it->second + "); keep one");
        }
    }
    if (allTeeth.size() > 1) throw Error(allTeeth[1], "all_teeth.obj is given twice (also " + allTeeth[0] + "); keep one");
    if (!allTeeth.empty() && !jc.toothPaths.empty())
        throw Error(allTeeth[0], "both tooth_<UNN> files and all_teeth.obj are present; keep one");
    if (!allTeeth.empty()) {
        jc.teethFromAllTeethObj = true;
        jc.allTeethPath = allTeeth[0];
    }
    if (jc.toothPaths.empty() && !jc.teethFromAllTeethObj)
        throw Error(jawDir.string(), "no teeth: expected teeth/tooth_<UNN>.stl files (or .obj, .ply, .off) or teeth/all_teeth.obj");

    const fs::path axes = jawDir / ("teeth_axes_" + name + ".json");
    if (isFile(axes)) jc.axesPath = axes.string();
    return jc;
}

}  // namespace

CaseInfo discoverCase(const std::string& caseDir) {
    if (!fs::exists(caseDir)) throw Error(caseDir, "case folder does not exist");
    if (!isDir(caseDir)) throw Error(caseDir, "is not a folder (expected a case folder holding input/)");
    const fs::path input = fs::path(caseDir) / "input";
    if (!isDir(input)) throw Error(caseDir, "no input/ folder (expected input/<mandible|maxilla>/bone and teeth)");
    CaseInfo info;
    info.root = caseDir;
    for (Jaw jaw : {Jaw::Mandible, Jaw::Maxilla}) {
        const fs::path jawDir = input / jawName(jaw);
        if (isDir(jawDir)) info.jaws.push_back(discoverJaw(jawDir, jaw));
    }
    if (info.jaws.empty()) throw Error(input.string(), "no jaw: expected a mandible/ or maxilla/ folder");
    return info;
}

// ---------------------------------------------------------------------------------------------
// Numbering an all_teeth.obj along the arch.

namespace {


struct UnionFind {
    std::vector<std::int32_t> parent;
    explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
    std::int32_t find(std::int32_t a) {
        while (parent[static_cast<std::size_t>(a)] != a) {
            parent[static_cast<std::size_t>(a)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(a)])];
            a = parent[static_cast<std::size_t>(a)];
        }
        return a;
    }
    void unite(std::int32_t a, std::int32_t b) {
        a = find(a);
        b = find(b);
        if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
};

/// Triangle lists of the connected components (vertices at equal positions count as shared),
/// ordered by their first triangle.
std::vector<std::vector<std::size_t>> components(const SurfaceMesh& mesh) {
    const std::size_t nv = mesh.vertices.size();
    UnionFind uf(nv);
    std::vector<std::int32_t> order(nv);
    std::iota(order.begin(), order.end(), 0);
    auto less = [&](std::int32_t a, std::int32_t b) {
        const Vec3& p = mesh.vertices[static_cast<std::size_t>(a)];
        const Vec3& q = mesh.vertices[static_cast<std::size_t>(b)];
        return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
    };
    std::sort(order.begin(), order.end(), less);
    for (std::size_t i = 1; i < nv; ++i)
        if (!less(order[i - 1], order[i])) uf.unite(order[i - 1], order[i]);
    for (const Tri& t : mesh.triangles) {
        uf.unite(t[0], t[1]);
        uf.unite(t[0], t[2]);
    }
    std::map<std::int32_t, std::size_t> index;
    std::vector<std::vector<std::size_t>> result;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto [it, inserted] = index.emplace(uf.find(mesh.triangles[t][0]), result.size());
        if (inserted) result.emplace_back();
        result[it->second].push_back(t);
    }
    return result;
}

SurfaceMesh extract(const SurfaceMesh& mesh, const std::vector<std::size_t>& triangles) {
    SurfaceMesh out;
    std::map<std::int32_t, std::int32_t> remap;
    for (std::size_t t : triangles) {
        Tri tri;
        for (std::size_t j = 0; j < 3; ++j) {
            const std::int32_t v = mesh.triangles[t][j];
            const auto [it, inserted] = remap.emplace(v, static_cast<std::int32_t>(out.vertices.size()));
            if (inserted) out.vertices.push_back(mesh.vertices[static_cast<std::size_t>(v)]);
            tri[j] = it->second;
        }
        out.triangles.push_back(tri);
    }
    return out;
}

Vec3 areaCentroid(const SurfaceMesh& mesh) {
    Vec3 sum = Vec3::Zero();
    double area = 0;
    for (const Tri& t : mesh.triangles) {
        const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
        const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
        const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
        const double w = 0.5 * (b - a).cross(c - a).norm();
        sum += w * (a + b + c) / 3.0;
        area += w;
    }
    if (area > 0) return sum / area;
    Vec3 mean = Vec3::Zero();
    for (const Vec3& v : mesh.vertices) mean += v;
    return mean / static_cast<double>(std::max<std::size_t>(1, mesh.vertices.size()));
}

bool contains(const BBox& outer, const BBox& inner) {
    return (outer.min.array() <= inner.min.array()).all() && (inner.max.array() <= outer.max.array()).all();
}

}  // namespace

std::map<int, SurfaceMesh> numberTeethAlongArch(const SurfaceMesh& allTeeth, Jaw jaw, const SurfaceMesh& bone,
                                                std::vector<std::string>* notes) {
    std::vector<std::vector<std::size_t>> parts = components(allTeeth);
    if (parts.empty()) throw Error("all_teeth: no triangles to split into teeth");

    // Join shells nested in another component's box (pulp cavities); drop specks.
    std::vector<BBox> boxes(parts.size());
    for (std::size_t i = 0; i < parts.size(); ++i)
        for (std::size_t t : parts[i])
            for (std::int32_t v : allTeeth.triangles[t]) boxes[i].extend(allTeeth.vertices[static_cast<std::size_t>(v)]);
    std::vector<double> diagonals;
    for (const BBox& b : boxes) diagonals.push_back(b.size().norm());
    std::nth_element(diagonals.begin(), diagonals.begin() + static_cast<std::ptrdiff_t>(diagonals.size() / 2), diagonals.end());
    const double medianDiagonal = diagonals[diagonals.size() / 2];
    std::vector<std::size_t> container(parts.size(), parts.size());  // largest box holding part i
    for (std::size_t i = 0; i < parts.size(); ++i)
        for (std::size_t j = 0; j < parts.size(); ++j) {
            const bool holds = j != i && contains(boxes[j], boxes[i]) && !(contains(boxes[i], boxes[j]) && j > i);
            if (holds && (container[i] == parts.size() || boxes[j].size().prod() > boxes[container[i]].size().prod()))
                container[i] = j;
        }
    auto root = [&](std::size_t i) {
        for (std::size_t steps = 0; container[i] != parts.size() && steps < parts.size(); ++steps) i = container[i];
        return i;
    };
    std::vector<std::vector<std::size_t>> teethParts;
    std::vector<BBox> teethBoxes;
    std::size_t dropped = 0, joined = 0;
    for (std::size_t i = 0; i < parts.size(); ++i) {
        if (container[i] != parts.size()) continue;
        if (boxes[i].size().norm() < 0.2 * medianDiagonal) {
            ++dropped;
            continue;
        }
        std::vector<std::size_t> tris = parts[i];
        for (std::size_t j = 0; j < parts.size(); ++j)
            if (j != i && container[j] != parts.size() && root(j) == i) {
                tris.insert(tris.end(), parts[j].begin(), parts[j].end());
                ++joined;
            }
        std::sort(tris.begin(), tris.end());
        teethParts.push_back(std::move(tris));
        teethBoxes.push_back(boxes[i]);
    }
    if (teethParts.empty()) throw Error("all_teeth: no component large enough to be a tooth");
    const std::size_t n = teethParts.size();
    std::vector<SurfaceMesh> teeth;
    std::vector<Vec3> centroids;
    for (const auto& tris : teethParts) {
        teeth.push_back(extract(allTeeth, tris));
        centroids.push_back(areaCentroid(teeth.back()));
    }
    Vec3 mean = Vec3::Zero();
    for (const Vec3& c : centroids) mean += c;
    mean /= static_cast<double>(n);

    // Occlusal plane normal, then its occlusal sign from the bone around the roots.
    Vec3 normal = Vec3::UnitZ();
    if (n >= 3) {
        Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
        for (const Vec3& c : centroids) cov += (c - mean) * (c - mean).transpose();
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
        normal = eig.eigenvectors().col(0).normalized();
        if (normal.z() < 0) normal = -normal;
    }
    double vote = 0;
    for (std::size_t i = 0; i < n; ++i) {
        BBox near = teethBoxes[i];
        near.min.array() -= 1.0;
        near.max.array() += 1.0;
        Vec3 sum = Vec3::Zero();
        std::size_t count = 0;
        for (const Vec3& v : bone.vertices)
            if ((v.array() >= near.min.array()).all() && (v.array() <= near.max.array()).all()) {
                sum += v;
                ++count;
            }
        if (count > 0) vote += (centroids[i] - sum / static_cast<double>(count)).dot(normal);
    }
    const bool fromBone = vote != 0;
    Vec3 occlusal = fromBone ? (vote > 0 ? normal : Vec3(-normal)) : (jaw == Jaw::Mandible ? normal : Vec3(-normal));
    const Vec3 superior = jaw == Jaw::Mandible ? occlusal : Vec3(-occlusal);

    // Order along the arch: angle around the mean centroid, starting after the largest gap.
    const Vec3 e1 = (std::abs(superior.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(superior).normalized();
    const Vec3 e2 = superior.cross(e1);
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::vector<double> angle(n);
    for (std::size_t i = 0; i < n; ++i) angle[i] = std::atan2((centroids[i] - mean).dot(e2), (centroids[i] - mean).dot(e1));
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return angle[a] < angle[b]; });
    std::size_t start = 0;
    double widest = -1;
    for (std::size_t k = 0; k < n; ++k) {
        const double prev = angle[order[(k + n - 1) % n]];
        double gap = angle[order[k]] - prev;
        if (gap <= 0) gap += 2 * kPi;
        if (gap > widest) {
            widest = gap;
            start = k;
        }
    }
    std::rotate(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(start), order.end());

    Vec3 anterior = -Vec3::UnitY();
    if (n >= 3) {
        const Vec3 d = mean - 0.5 * (centroids[order.front()] + centroids[order.back()]);
        const Vec3 inPlane = d - d.dot(superior) * superior;
        if (inPlane.norm() > 1e-9) anterior = inPlane.normalized();
    }
    const Vec3 left = superior.cross(anterior);
    if (n >= 2 && (centroids[order.front()] - centroids[order.back()]).dot(left) < 0) std::reverse(order.begin(), order.end());

    // Midline: between the adjacent pair whose midpoint is most anterior.
    std::size_t lastLeft = 0;
    if (n >= 2) {
        double best = -std::numeric_limits<double>::infinity();
        for (std::size_t k = 0; k + 1 < n; ++k) {
            const double a = (0.5 * (centroids[order[k]] + centroids[order[k + 1]])).dot(anterior);
            if (a > best) {
                best = a;
                lastLeft = k;
            }
        }
    } else if ((centroids[0] - mean).dot(left) < 0) {
        lastLeft = std::numeric_limits<std::size_t>::max();  // the single tooth is on the right
    }
    const std::size_t leftCount = lastLeft == std::numeric_limits<std::size_t>::max() ? 0 : lastLeft + 1;
    const std::size_t rightCount = n - leftCount;
    if (leftCount > 8 || rightCount > 8)
        throw Error("all_teeth: " + std::to_string(leftCount) + " teeth on the patient's left and " +
                    std::to_string(rightCount) + " on the right; at most 8 per side can be numbered");
    const int leftCentral = jaw == Jaw::Mandible ? 24 : 9, leftStep = jaw == Jaw::Mandible ? -1 : 1;
    const int rightCentral = jaw == Jaw::Mandible ? 25 : 8, rightStep = jaw == Jaw::Mandible ? 1 : -1;

    std::map<int, SurfaceMesh> result;
    std::ostringstream note;
    note << "all_teeth: " << n << " teeth numbered along the arch (patient left to right):";
    for (std::size_t k = 0; k < n; ++k) {
        const int unn = k < leftCount ? leftCentral + leftStep * static_cast<int>(leftCount - 1 - k)
                                      : rightCentral + rightStep * static_cast<int>(k - leftCount);
        note << ' ' << unn;
        result.emplace(unn, std::move(teeth[order[k]]));
    }
    note << "; occlusal side from " << (fromBone ? "the bone around the roots" : "the +z convention");
    if (joined) note << "; " << joined << " nested shell(s) joined to their tooth";
    if (dropped) note << "; " << dropped << " tiny component(s) dropped";
    if (notes) notes->push_back(note.str());
    return result;
}

// ---------------------------------------------------------------------------------------------

JawSurfaces loadJaw(const JawCase& jc, const LoadOptions& options, Progress& progress) {
    if (!(options.scale >= 0) || !std::isfinite(options.scale))
        throw Error(jc.bonePath, "scale must be a positive number (or 0 for automatic), not " + std::to_string(options.scale));
    JawSurfaces out;
    out.jaw = jc.jaw;

    std::vector<std::string> paths{jc.bonePath};
    std::vector<int> unns{0};
    if (jc.teethFromAllTeethObj) {
        paths.push_back(jc.allTeethPath);
        unns.push_back(0);
    }
    for (const auto& [unn, path] : jc.toothPaths) {
        paths.push_back(path);
        unns.push_back(unn);
    }
    std::vector<SurfaceMesh> meshes(paths.size());
    std::vector<std::exception_ptr> errors(paths.size());
    {
        ProgressStage stage(progress, "read " + jawName(jc.jaw) + " surfaces");
        std::atomic<std::size_t> done{0};
        tbb::parallel_for(std::size_t(0), paths.size(), [&](std::size_t i) {
            try {
                progress.checkCancelled();
                meshes[i] = readSurface(paths[i]);
            } catch (...) {
                errors[i] = std::current_exception();
            }
            stage.update(static_cast<double>(++done) / static_cast<double>(paths.size()));
        });
        for (const auto& e : errors)  // the first failing file in a fixed order, whatever the threads
            if (e) std::rethrow_exception(e);
    }
    out.bone = std::move(meshes[0]);
    if (!jc.axesPath.empty()) out.axes = readToothAxes(jc.axesPath);

    if (options.scale > 0) {
        auto scale = [&](SurfaceMesh& m) {
            for (Vec3& v : m.vertices) v *= options.scale;
        };
        scale(out.bone);
        for (std::size_t i = 1; i < meshes.size(); ++i) scale(meshes[i]);
        for (auto& [unn, a] : out.axes) a.crownCentre *= options.scale;
        out.notes.push_back("coordinates multiplied by " + std::to_string(options.scale));
    } else {
        BBox box = boundingBox(out.bone);
        for (std::size_t i = 1; i < meshes.size(); ++i) box.extend(boundingBox(meshes[i]));
        const double diagonal = box.size().norm();
        if (diagonal < 1.0 || diagonal > 1000.0) {
            std::ostringstream msg;
            msg << "the " << jawName(jc.jaw) << " case's bounding box diagonal is " << diagonal << " but should be in "
                << "millimetres (between 1 and 1000): the coordinates look like "
                << (diagonal < 1.0 ? "metres (pass scale 1000)" : "micrometres or another unit (pass an explicit scale)")
                << "; an explicit scale multiplies every coordinate and skips this check";
            throw Error(jc.bonePath, msg.str());
        }
    }

    if (jc.teethFromAllTeethObj) {
        std::vector<std::string> notes;
        try {
            out.teeth = numberTeethAlongArch(meshes[1], jc.jaw, out.bone, &notes);
        } catch (const Error& e) {
            throw Error(jc.allTeethPath, e.reason());
        }
        for (const auto& [unn, tooth] : out.teeth)
            if (jawOfTooth(unn) != jc.jaw) throw Error(jc.allTeethPath, "numbering gave tooth " + std::to_string(unn) + " of the other jaw");
        out.notes.insert(out.notes.end(), notes.begin(), notes.end());
    } else {
        for (std::size_t i = 1; i < meshes.size(); ++i) out.teeth.emplace(unns[i], std::move(meshes[i]));
    }
    for (const auto& [unn, a] : out.axes)
        if (!out.teeth.count(unn))
            out.notes.push_back(jc.axesPath + ": axes of tooth " + std::to_string(unn) + " ignored (no such tooth)");
    return out;
}

std::string toothSource(const JawCase& jawCase, int unn) {
    const auto file = jawCase.toothPaths.find(unn);
    if (file != jawCase.toothPaths.end()) return file->second;
    return jawCase.allTeethPath + " (tooth " + std::to_string(unn) + ")";
}

}  // namespace jawmesh
