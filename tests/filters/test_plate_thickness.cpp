// Thin plates of a region: the thickness found along vertex normals on closed boxes and prisms
// whose thickness or angle is known, and what is not a plate (thick boxes, open wedges, the outside).
#include "filters/PlateThickness.h"
#include "io/Angles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

namespace jawmesh {
namespace {


/// Builds a closed complex face by face; coincident vertices are merged.
struct ComplexBuilder {
    InterfaceComplex c;
    std::map<std::array<long long, 3>, std::int32_t> ids;

    std::int32_t vertex(const Vec3& p) {
        const std::array<long long, 3> key{std::llround(p.x() * 1e9), std::llround(p.y() * 1e9), std::llround(p.z() * 1e9)};
        const auto [it, fresh] = ids.emplace(key, std::int32_t(c.surface.vertices.size()));
        if (fresh) c.surface.vertices.push_back(p);
        return it->second;
    }
    /// Quad o, o + u, o + u + w, o + w as an nu x nw grid; u x w points into `inside`.
    void quad(const Vec3& o, const Vec3& u, const Vec3& w, int nu, int nw, Label inside, Label other) {
        const auto at = [&](int i, int j) { return vertex(o + u * (double(i) / nu) + w * (double(j) / nw)); };
        for (int i = 0; i < nu; ++i)
            for (int j = 0; j < nw; ++j) {
                triangle({at(i, j), at(i + 1, j), at(i + 1, j + 1)}, inside, other);
                triangle({at(i, j), at(i + 1, j + 1), at(i, j + 1)}, inside, other);
            }
    }
    void triangle(const Tri& f, Label inside, Label other) {
        c.surface.triangles.push_back(f);
        c.sides.push_back({inside, other});
    }
};

/// Box [0,1] x [0,1] x [0,t] of region 1 in the outside, n x n triangles pairs on the big faces.
InterfaceComplex box(double t, int n) {
    ComplexBuilder b;
    const Vec3 X(1, 0, 0), Y(0, 1, 0), Z(0, 0, t);
    b.quad({0, 0, 0}, X, Y, n, n, 1, 0);  // bottom, normal +z (inwards)
    b.quad(Z, Y, X, n, n, 1, 0);          // top, normal -z
    b.quad({0, 0, 0}, Y, Z, n, 1, 1, 0);  // x = 0, normal +x
    b.quad(X, Z, Y, 1, n, 1, 0);          // x = 1, normal -x
    b.quad({0, 0, 0}, Z, X, 1, n, 1, 0);  // y = 0, normal +y
    b.quad(Y, X, Z, n, 1, 1, 0);          // y = 1, normal -y
    return b.c;
}

TEST(PlateThickness, ThinBoxIsAPlateOfItsThicknessThickBoxIsNot) {
    const InterfaceComplex thin = box(0.03, 10);
    const std::vector<float> t = plateThicknessMm(thin, {});
    std::size_t inner = 0;
    for (std::size_t v = 0; v < t.size(); ++v) {
        const Vec3& p = thin.surface.vertices[v];
        const bool onBigFaceInside = p.x() > 1e-9 && p.x() < 1 - 1e-9 && p.y() > 1e-9 && p.y() < 1 - 1e-9;
        if (!onBigFaceInside) continue;  // box edges: their normals lean 45 degrees, no plate
        ++inner;
        EXPECT_NEAR(t[v], 0.03, 1e-6) << "vertex " << v;
    }
    EXPECT_EQ(inner, 2u * 9u * 9u);

    const std::vector<float> thick = plateThicknessMm(box(0.3, 10), {});  // thicker than maxMm
    for (float x : thick) EXPECT_TRUE(std::isinf(x));

    // Only the vertices asked for are measured.
    std::vector<char> measure(thin.surface.vertices.size(), 0);
    std::size_t centre = 0;
    for (std::size_t v = 0; v < measure.size(); ++v)
        if ((thin.surface.vertices[v] - Vec3(0.5, 0.5, 0)).norm() < 1e-9) centre = v;
    measure[centre] = 1;
    const std::vector<float> some = plateThicknessMm(thin, measure);
    for (std::size_t v = 0; v < some.size(); ++v) {
        if (v == centre) {
            EXPECT_NEAR(some[v], 0.03, 1e-6);
        } else {
            EXPECT_TRUE(std::isinf(some[v])) << "vertex " << v;
        }
    }
}

TEST(PlateThickness, OutsideIsNeverAPlate) {
    // The same thin box with its labels swapped: the thin layer is now the outside.
    InterfaceComplex c = box(0.03, 6);
    for (auto& s : c.sides) std::swap(s[0], s[1]);  // the normals, into the box, now point into 0
    for (float x : plateThicknessMm(c, {})) EXPECT_TRUE(std::isinf(x));
}

/// Prism of region 1: the cross-section has its sharp corner on the y axis, legs of 1 mm at
/// `deg` degrees, extruded 1 mm along y; n steps along the legs.
InterfaceComplex wedge(double deg, int n) {
    ComplexBuilder b;
    const double a = deg * kPi / 180;
    const Vec3 A(1, 0, 0), B(std::cos(a), 0, std::sin(a)), Y(0, 1, 0);
    b.quad({0, 0, 0}, A, Y, n, n, 1, 0);  // leg on z = 0, normal +z (inwards)
    b.quad({0, 0, 0}, Y, B, n, n, 1, 0);  // leg at deg, normal (sin, 0, -cos)
    b.quad(A, B - A, Y, 1, 1, 1, 0);      // far side, normal towards the sharp edge
    b.triangle({b.vertex({0, 0, 0}), b.vertex(B), b.vertex(A)}, 1, 0);  // y = 0, normal +y
    b.triangle({b.vertex(Y), b.vertex(Y + A), b.vertex(Y + B)}, 1, 0);  // y = 1, normal -y
    // The far side and the caps are single triangles (not conforming to the legs' grids): only
    // vertices inside the floor leg are checked.
    return b.c;
}

TEST(PlateThickness, NarrowWedgeIsAPlateOpenWedgeIsNot) {
    const double narrow = 10;
    const InterfaceComplex c = wedge(narrow, 40);
    const std::vector<float> t = plateThicknessMm(c, {});
    std::size_t measured = 0;
    for (std::size_t v = 0; v < t.size(); ++v) {
        const Vec3& p = c.surface.vertices[v];
        const bool onFloor = std::abs(p.z()) < 1e-12 && p.y() > 1e-9 && p.y() < 1 - 1e-9 && p.x() > 1e-9 && p.x() < 1 - 1e-9;
        if (!onFloor) continue;
        // From the floor, along +z, the other leg is s tan(10 deg) away.
        const double expected = p.x() * std::tan(narrow * kPi / 180);
        if (expected < 0.099) {
            EXPECT_NEAR(t[v], expected, 1e-6) << "x " << p.x();
            ++measured;
        } else {
            EXPECT_TRUE(std::isinf(t[v])) << "x " << p.x();
        }
    }
    EXPECT_GT(measured, 50u);
    for (float x : plateThicknessMm(wedge(40, 40), {})) EXPECT_TRUE(std::isinf(x));
}

}  // namespace
}  // namespace jawmesh
