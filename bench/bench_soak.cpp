// bench_soak <dataset> [seeds=N] [teeth=a,b,...] [variants=clean,flips,...] [scale=0.25] [case=<dir>]:
// writes the soak dataset of issue #27, one phantom mandible case per seed x tooth count x dirty
// variant, named <variant>-t<teeth>-s<seed>, for `jawmesh batch` to run (bench/soak.sh runs it and
// tabulates). With case=<dir>, the variants of that real case's first jaw instead (<variant>-case).
// Variants (tests/support/DirtySurfaces.h), each as a segmentation export would leave the surfaces:
//   clean       the phantom as it is
//   flips       half of every surface's triangles reversed
//   holes       6 holes of 0.3-1.0 mm punched into the bone, one of 0.2-0.5 mm into every tooth
//   duplicates  20 % of the triangles repeated, half of them on their own vertices, some reversed
//   shells      every tooth with an overlapping inner shell (scaled 0.85 about its centroid)
//   staircase   every tooth as unsmoothed voxels of 0.2 mm (binary indicator, dual contouring)
#include "io/Case.h"
#include "io/Error.h"
#include "levelset/Phantom.h"
#include "support/DirtySurfaces.h"
#include "support/VoxelStaircase.h"

#include <openvdb/openvdb.h>

#include <cstdio>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace jawmesh;

std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');)
        if (!item.empty()) out.push_back(item);
    return out;
}

/// The first jaw of a case folder in the phantom's form (bone, teeth, axes), to be dirtied.
PhantomJaw caseJaw(const std::string& caseDir) {
    const JawSurfaces s = loadJaw(discoverCase(caseDir).jaws.at(0));
    PhantomJaw jaw;
    jaw.jaw = s.jaw;
    jaw.bone = s.bone;
    jaw.teeth = s.teeth;
    jaw.axes = s.axes;
    return jaw;
}

using Dirt = std::function<void(PhantomJaw&)>;

void eachTooth(PhantomJaw& jaw, const std::function<SurfaceMesh(const SurfaceMesh&)>& f) {
    for (auto& [unn, mesh] : jaw.teeth) mesh = f(mesh);
}

const std::map<std::string, Dirt>& variants() {
    static const std::map<std::string, Dirt> v = {
        {"clean", [](PhantomJaw&) {}},
        {"flips",
         [](PhantomJaw& j) {
             j.bone = test::flipHalf(j.bone);
             eachTooth(j, [](const SurfaceMesh& m) { return test::flipHalf(m); });
         }},
        {"holes",
         [](PhantomJaw& j) {
             j.bone = test::punchHoles(j.bone, 6, 0.3, 1.0);
             eachTooth(j, [](const SurfaceMesh& m) { return test::punchHoles(m, 1, 0.2, 0.5); });
         }},
        {"duplicates",
         [](PhantomJaw& j) {
             j.bone = test::duplicateFaces(j.bone, 0.2);
             eachTooth(j, [](const SurfaceMesh& m) { return test::duplicateFaces(m, 0.2); });
         }},
        {"shells", [](PhantomJaw& j) { eachTooth(j, [](const SurfaceMesh& m) { return test::withInnerShell(m, 0.85); }); }},
        {"staircase", [](PhantomJaw& j) { eachTooth(j, [](const SurfaceMesh& m) { return test::voxelStaircase(m, 0.2); }); }},
    };
    return v;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s <dataset> [seeds=4] [teeth=1,4,8,14] [variants=clean,flips,...] [scale=0.25]\n", argv[0]);
        return 2;
    }
    int seeds = 4;
    std::vector<std::string> teeth{"1", "4", "8", "14"}, names;
    double scale = 0.25;
    std::string realCase;
    for (const auto& [name, dirt] : variants()) names.push_back(name);
    for (int i = 2; i < argc; ++i) {
        const std::string a = argv[i];
        const std::string key = a.substr(0, a.find('=')), value = a.substr(a.find('=') + 1);
        if (key == "seeds") seeds = std::stoi(value);
        else if (key == "teeth") teeth = splitList(value);
        else if (key == "variants") names = splitList(value);
        else if (key == "scale") scale = std::stod(value);
        else if (key == "case") realCase = value;
        else { std::fprintf(stderr, "unknown key %s\n", key.c_str()); return 2; }
    }
    try {
        openvdb::initialize();
        int written = 0;
        for (const std::string& name : names) {
            const auto dirt = variants().find(name);
            if (dirt == variants().end()) throw Error("bench_soak: unknown variant " + name);
            if (!realCase.empty()) {
                PhantomJaw jaw = caseJaw(realCase);
                dirt->second(jaw);
                writePhantomCase({jaw}, std::string(argv[1]) + "/" + name + "-case");
                ++written;
                continue;
            }
            for (const std::string& count : teeth)
                for (int seed = 1; seed <= seeds; ++seed) {
                    PhantomOptions o;
                    o.teeth = std::stoi(count);
                    o.seed = static_cast<std::uint32_t>(seed);
                    o.trianglesScale = scale;
                    PhantomJaw jaw = makePhantom(o);
                    dirt->second(jaw);
                    writePhantomCase({jaw}, std::string(argv[1]) + "/" + name + "-t" + count + "-s" + std::to_string(seed));
                    ++written;
                }
        }
        std::printf("%d cases in %s\n", written, argv[1]);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_soak: %s\n", e.what());
        return 1;
    }
    return 0;
}
