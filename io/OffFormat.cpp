// OFF (Geomview object file format), text only: an "OFF" header (also COFF / NOFF / CNOFF, whose
// extra per-vertex values are ignored), '#' comments, "nv nf ne", nv vertex lines, nf polygon
// lines "k i0 .. ik-1 [colour]". Polygons are fan-triangulated.
#include "io/detail/MeshFormats.h"

#include <vector>

namespace jawmesh::detail {
namespace {

/// Next line that is not blank once its '#' comment is cut; false at the end.
bool nextDataLine(LineReader& lines, std::string_view& line) {
    while (lines.next(line)) {
        const auto hash = line.find('#');
        if (hash != std::string_view::npos) line = line.substr(0, hash);
        if (!Tokens(line).atEnd()) return true;
    }
    return false;
}

}  // namespace

SurfaceMesh readOff(const std::string& path, std::string_view data) {
    requireText(path, data, "OFF");
    LineReader lines(data);
    std::string_view line;
    auto fail = [&](const std::string& what) {
        throw Error(path, "line " + std::to_string(lines.lineNumber()) + ": " + what);
    };
    if (!nextDataLine(lines, line)) throw Error(path, "file holds no OFF header");
    Tokens header(line);
    const std::string_view magic = header.next();
    if (magic.size() < 3 || magic.substr(magic.size() - 3) != "OFF" || magic.find_first_not_of("STCNO4nF") != std::string_view::npos)
        fail("expected an 'OFF' header, found " + quoted(magic));
    if (magic.find('4') != std::string_view::npos || magic.find('n') != std::string_view::npos)
        fail("only 3-dimensional OFF is supported");
    const std::string_view afterMagic = header.next();
    if (afterMagic == "BINARY") fail("binary OFF is not supported; convert it to text OFF, PLY or STL");

    // The counts may follow the header on the same line.
    Tokens counts = afterMagic.empty() ? Tokens(std::string_view()) : Tokens(line.substr(afterMagic.data() - line.data()));
    if (afterMagic.empty()) {
        if (!nextDataLine(lines, line)) throw Error(path, "file ends before the 'vertices faces edges' counts line");
        counts = Tokens(line);
    }
    std::int64_t nv = 0, nf = 0;
    const std::string_view nvToken = counts.next(), nfToken = counts.next();
    if (!parseInt(nvToken, nv) || !parseInt(nfToken, nf) || nv < 0 || nf < 0)
        fail("expected 'vertices faces edges' counts, found " + quoted(nvToken) + " " + quoted(nfToken));
    // Every vertex line holds at least 6 characters ("0 0 0\n"), every face line at least 8.
    const auto remaining = static_cast<std::int64_t>(lines.remaining());
    if (nv > remaining / 6 + 1 || nf > remaining / 8 + 1 || nv > static_cast<std::int64_t>(kMaxElements))
        fail("header promises " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
             " faces, more than the file's " + std::to_string(remaining) + " remaining bytes can hold (truncated?)");

    SurfaceMesh mesh;
    mesh.vertices.reserve(static_cast<std::size_t>(nv));
    for (std::int64_t i = 0; i < nv; ++i) {
        if (!nextDataLine(lines, line))
            throw Error(path, "file ends after " + std::to_string(i) + " of the " + std::to_string(nv) + " vertices it promises (truncated)");
        Tokens tokens(line);
        double xyz[3];
        for (double& v : xyz) {
            const std::string_view token = tokens.next();
            if (!parseDouble(token, v)) fail("vertex coordinate " + quoted(token) + " is not a finite number");
        }
        mesh.vertices.emplace_back(xyz[0], xyz[1], xyz[2]);
    }
    mesh.triangles.reserve(static_cast<std::size_t>(nf));
    std::vector<std::int32_t> polygon;
    for (std::int64_t f = 0; f < nf; ++f) {
        if (!nextDataLine(lines, line))
            throw Error(path, "file ends after " + std::to_string(f) + " of the " + std::to_string(nf) + " faces it promises (truncated)");
        Tokens tokens(line);
        std::int64_t k = 0;
        const std::string_view kToken = tokens.next();
        if (!parseInt(kToken, k) || k < 3 || k > static_cast<std::int64_t>(line.size()))
            fail("face corner count " + quoted(kToken) + " is not a number of at least 3");
        polygon.clear();
        for (std::int64_t j = 0; j < k; ++j) {
            const std::string_view token = tokens.next();
            std::int64_t index = 0;
            if (!parseInt(token, index)) fail("face index " + quoted(token) + " is not an integer (face too short?)");
            if (index < 0 || index >= nv)
                fail("face index " + std::to_string(index) + " outside 0.." + std::to_string(nv - 1));
            polygon.push_back(static_cast<std::int32_t>(index));
        }
        for (std::size_t j = 1; j + 1 < polygon.size(); ++j) {
            if (mesh.triangles.size() >= kMaxElements) fail("more than 2^31-1 triangles");
            mesh.triangles.push_back({polygon[0], polygon[j], polygon[j + 1]});
        }
    }
    validateMesh(path, mesh);
    return mesh;
}

}  // namespace jawmesh::detail
