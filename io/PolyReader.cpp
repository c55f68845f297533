// Implements io/PolyReader.h; what it computes, its rules and its contract are documented there.
#include "io/PolyReader.h"

#include "io/Error.h"

#include <fstream>
#include <sstream>

namespace jawmesh {
namespace {

/// The file's numbers, comments ('#' to the end of the line) left out.
class Tokens {
public:
    explicit Tokens(const std::string& path) : path_(path) {
        std::ifstream in(path);
        if (!in) throw Error(path, "cannot open the file");
        std::string text, line;
        while (std::getline(in, line)) text += line.substr(0, line.find('#')) + '\n';
        words_.str(text);
    }
    template <class T>
    T next(const char* what) {
        T v{};
        if (!(words_ >> v)) throw Error(path_, std::string("expected ") + what);
        return v;
    }

private:
    std::string path_;
    std::istringstream words_;
};

}  // namespace

InterfaceComplex readTetgenPoly(const std::string& path) {
    Tokens in(path);
    InterfaceComplex c;
    const auto nv = in.next<std::int64_t>("the node count");
    if (nv < 0 || in.next<int>("the dimension") != 3) throw Error(path, "expected 3D nodes");
    const int attributes = in.next<int>("the node attribute count");
    const int markers = in.next<int>("the node marker flag");
    c.surface.vertices.resize(std::size_t(nv));
    for (auto& p : c.surface.vertices) {
        in.next<std::int64_t>("a node index");
        for (int k = 0; k < 3; ++k) p[k] = in.next<double>("a coordinate");
        for (int a = 0; a < attributes + (markers ? 1 : 0); ++a) in.next<double>("a node attribute");
    }
    const auto nf = in.next<std::int64_t>("the facet count");
    if (in.next<int>("the facet marker flag") != 1) throw Error(path, "facets without markers carry no labels");
    for (std::int64_t f = 0; f < nf; ++f) {
        if (in.next<int>("a polygon count") != 1 || in.next<int>("a hole count") != 0)
            throw Error(path, "facet " + std::to_string(f) + " is not a single polygon");
        const int marker = in.next<int>("a facet marker");
        if (in.next<int>("a polygon size") != 3) throw Error(path, "facet " + std::to_string(f) + " is not a triangle");
        Tri t;
        for (auto& v : t) {
            v = in.next<std::int32_t>("a node index") - 1;
            if (v < 0 || v >= nv) throw Error(path, "facet " + std::to_string(f) + " has a node index out of range");
        }
        c.surface.triangles.push_back(t);
        c.sides.push_back(interfacePairFromMarker(marker));
    }
    if (in.next<int>("the hole count") != 0) throw Error(path, "holes are not supported");
    const auto nr = in.next<std::int64_t>("the region count");
    for (std::int64_t r = 0; r < nr; ++r) {
        in.next<std::int64_t>("a region index");
        RegionSeed s;
        for (int k = 0; k < 3; ++k) s.point[k] = in.next<double>("a seed coordinate");
        s.label = Label(in.next<double>("a region attribute"));
        in.next<double>("a region volume bound");
        c.seeds.push_back(s);
    }
    return c;
}

}  // namespace jawmesh
