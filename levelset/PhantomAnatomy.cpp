// Implements levelset/PhantomAnatomy.h; what it computes, its rules and its contract are documented there.
#include "levelset/PhantomAnatomy.h"

#include "io/Angles.h"
#include "io/Error.h"
#include "levelset/PhantomRandom.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace jawmesh::phantom {
namespace {

constexpr double kDeg = kPi / 180.0;
constexpr double kOcclusalHalfGapMm = 0.5;  // crowns stop this far from the occlusal plane z = 0
constexpr double kCrestBelowCejMm = 1.75;   // alveolar crest apical of the crown-root junction
constexpr double kContactGapMm = 0.6;       // designed gap between adjacent crowns along the arch

// Polynomial smooth minimum / maximum with blend radius k (mm).
double smin(double a, double b, double k) {
    const double h = std::max(k - std::abs(a - b), 0.0) / k;
    return std::min(a, b) - h * h * k * 0.25;
}
double smax(double a, double b, double k) { return -smin(-a, -b, k); }

double smoothstep01(double t) {
    t = std::clamp(t, 0.0, 1.0);
    return t * t * (3 - 2 * t);
}

// Uniform in [-1, 1], a function of (seed, tooth, parameter) only: a tooth's shape does not depend
// on which other teeth are generated.
double jitter(std::uint32_t seed, int unn, int param) {
    return unitFromHash(splitMix64(splitMix64(splitMix64(seed) ^ static_cast<std::uint64_t>(unn)) ^ static_cast<std::uint64_t>(param)));
}

// Round cone between a (radius r1) and b (radius r2); exact distance (Quilez).
double roundCone(const Vec3& p, const Vec3& a, const Vec3& b, double r1, double r2) {
    const Vec3 ba = b - a;
    const double l2 = ba.squaredNorm();
    const double rr = r1 - r2;
    const double a2 = l2 - rr * rr;
    const double il2 = 1.0 / l2;
    const Vec3 pa = p - a;
    const double y = pa.dot(ba);
    const double z = y - l2;
    const double x2 = (pa * l2 - ba * y).squaredNorm();
    const double y2 = y * y * l2;
    const double z2 = z * z * l2;
    const double k = (rr > 0 ? 1.0 : (rr < 0 ? -1.0 : 0.0)) * rr * rr * x2;
    if ((z > 0 ? 1.0 : -1.0) * a2 * z2 > k) return std::sqrt(x2 + z2) * il2 - r2;
    if ((y > 0 ? 1.0 : -1.0) * a2 * y2 < k) return std::sqrt(x2 + y2) * il2 - r1;
    return (std::sqrt(x2 * a2 * il2) + y * rr) * il2 - r1;
}

// Crown half-width profile over t = height / crown height in [0, 1]: rises from `cervical` to 1 at
// the height of contour, then falls to `top`.
double crownProfile(double t, double cervical, double contour, double top) {
    t = std::clamp(t, 0.0, 1.0);
    if (t < contour) {
        const double s = 1.0 - t / contour;
        return cervical + (1.0 - cervical) * (1.0 - s * s);
    }
    const double s = (t - contour) / (1.0 - contour);
    return 1.0 - (1.0 - top) * s * s;
}

// Tooth sizes (mm) and shape ratios by jaw and kind: typical adult values.
ToothSpec baseSpec(Jaw jaw, ToothKind kind) {
    ToothSpec t;
    t.kind = kind;
    t.frame.setIdentity();
    const bool lower = jaw == Jaw::Mandible;
    auto incisor = [&](double hmd, double hbl, double h, double l, double inclDeg) {
        t.halfMd = hmd; t.halfBl = hbl; t.crownHeight = h; t.rootLength = l;
        t.cervicalMd = lower ? 0.65 : 0.72; t.cervicalBl = 0.88;
        t.contourHeightMd = 0.75; t.contourHeightBl = 0.2;
        t.topMd = 0.97; t.topBl = 0.3; t.crossExponent = 2.2; t.rootBend = 0.3;
        t.inclinationTan = std::tan(inclDeg * kDeg);
    };
    auto premolar = [&](double hmd, double hbl, double h, double l, double lingualCusp) {
        t.halfMd = hmd; t.halfBl = hbl; t.crownHeight = h; t.rootLength = l;
        t.cervicalMd = 0.7; t.cervicalBl = 0.85; t.contourHeightMd = 0.6; t.contourHeightBl = 0.35;
        t.topMd = 0.85; t.topBl = 0.75; t.crossExponent = 2.5; t.rootBend = 0.6; t.fossaDepth = 2.0;
        t.cusps = {{0.0, (lower ? 0.35 : 0.45) * hbl, 2.0, 0.45 * hmd * 2},
                   {0.0, -0.45 * hbl, lingualCusp, 0.4 * hmd * 2}};
    };
    auto molar = [&](double hmd, double hbl, double h, double l, double trunk, double inclDeg) {
        t.halfMd = hmd; t.halfBl = hbl; t.crownHeight = h; t.rootLength = l; t.trunkLength = trunk;
        t.cervicalMd = 0.8; t.cervicalBl = 0.85; t.contourHeightMd = 0.55; t.contourHeightBl = 0.35;
        t.topMd = 0.88; t.topBl = 0.8; t.crossExponent = 3.0; t.rootBend = 0.8; t.fossaDepth = 2.0;
        t.inclinationTan = std::tan(inclDeg * kDeg);
        const double a = hmd, b = hbl, s = 0.3 * hmd;
        const double T = trunk;
        if (lower) {
            t.cusps = {{-0.55 * a, 0.5 * b, 1.8, s}, {0.0, 0.55 * b, 1.8, s}, {0.6 * a, 0.45 * b, 1.6, s},
                       {-0.5 * a, -0.5 * b, 2.0, s}, {0.45 * a, -0.5 * b, 2.0, s}};
            t.roots = {{Vec3(-0.5 * a, 0, -T + 1.0), Vec3(-0.5 * a + 0.3, 0, -l), 0.36 * a, 0.7, 0.36 * a / (0.8 * b)},
                       {Vec3(0.5 * a, 0, -T + 1.0), Vec3(0.65 * a, 0, -l + 1.0), 0.33 * a, 0.7, 0.33 * a / (0.75 * b)}};
        } else {
            t.cusps = {{-0.5 * a, 0.5 * b, 1.8, s}, {0.5 * a, 0.5 * b, 1.6, s},
                       {-0.35 * a, -0.45 * b, 2.2, 0.38 * a}, {0.5 * a, -0.5 * b, 1.4, s}};
            t.roots = {{Vec3(-0.45 * a, 0.4 * b, -T + 1.0), Vec3(-0.5 * a, 0.55 * b, -l), 0.32 * a, 0.6, 0.32 * a / (0.5 * b)},
                       {Vec3(0.45 * a, 0.4 * b, -T + 1.0), Vec3(0.6 * a, 0.5 * b, -l + 1.5), 0.28 * a, 0.55, 0.28 * a / (0.4 * b)},
                       {Vec3(0.0, -0.45 * b, -T + 1.0), Vec3(0.0, -0.45 * b - 2.5, -l - 0.5), 0.38 * a, 0.7, 1.0}};
        }
    };
    switch (kind) {
    case ToothKind::CentralIncisor: lower ? incisor(2.7, 3.0, 9.0, 12.5, 8) : incisor(4.25, 3.5, 10.5, 13.0, 12); break;
    case ToothKind::LateralIncisor: lower ? incisor(2.95, 3.1, 9.5, 14.0, 8) : incisor(3.25, 3.0, 9.0, 13.0, 10); break;
    case ToothKind::Canine:
        incisor(lower ? 3.5 : 3.75, lower ? 3.85 : 4.0, lower ? 11.0 : 10.0, lower ? 16.0 : 17.0, 5);
        t.cervicalMd = 0.75; t.cervicalBl = 0.92; t.contourHeightMd = 0.6; t.contourHeightBl = 0.3;
        t.topMd = 0.45; t.topBl = 0.45; t.cuspSlope = 0.5; t.rootBend = 0.5;
        break;
    case ToothKind::FirstPremolar: lower ? premolar(3.5, 3.85, 8.5, 14.0, 1.0) : premolar(3.5, 4.5, 8.5, 14.0, 1.8); break;
    case ToothKind::SecondPremolar: lower ? premolar(3.6, 4.1, 8.0, 14.5, 1.5) : premolar(3.4, 4.5, 7.8, 14.0, 1.8); break;
    case ToothKind::FirstMolar: lower ? molar(5.6, 5.25, 7.5, 14.0, 3.5, -6) : molar(5.0, 5.5, 7.5, 13.0, 4.0, 3); break;
    case ToothKind::SecondMolar: lower ? molar(5.25, 5.0, 7.0, 13.0, 3.5, -8) : molar(4.5, 5.5, 7.0, 13.0, 4.0, 3); break;
    case ToothKind::ThirdMolar: lower ? molar(5.0, 4.75, 6.5, 11.0, 3.0, -10) : molar(4.25, 5.0, 6.5, 11.0, 3.5, 3); break;
    }
    return t;
}

// Scales a spec's sizes (crown by c, root by r), keeping its shape ratios.
void scaleSpec(ToothSpec& t, double c, double r) {
    t.halfMd *= c; t.halfBl *= c; t.crownHeight *= c; t.rootLength *= r; t.trunkLength *= r;
    for (Cusp& k : t.cusps) { k.u *= c; k.v *= c; k.sigma *= c; }
    for (RootCone& k : t.roots) {
        k.top = Vec3(k.top.x() * c, k.top.y() * c, k.top.z() * r);
        k.apex = Vec3(k.apex.x() * c, k.apex.y() * c, k.apex.z() * r);
        k.radiusTop *= c;
    }
}

// How far the roots reach labially/lingually beyond the crown, for the bone thickness.
double rootSpread(const ToothSpec& t) {
    double spread = 0;
    for (const RootCone& r : t.roots)
        spread = std::max(spread, std::abs(r.apex.y()) + r.radiusApex / r.vScale - t.halfBl);
    return std::max(spread, 0.0);
}

BBox transformedBox(const Vec3& origin, const Eigen::Matrix3d& frame, const Vec3& lo, const Vec3& hi) {
    BBox box;
    for (int c = 0; c < 8; ++c) {
        const Vec3 q((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(), (c & 4) ? hi.z() : lo.z());
        box.extend(Vec3(origin + frame * q));
    }
    return box;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Arch

Arch::Arch(double halfLength, double scale) : halfLength_(halfLength), step_(0.25) {
    // Tangent angle grows from 0 at the midline to ~83 degrees: a rounded front, nearly straight,
    // slightly diverging posterior segments (canine ~14 mm lateral, first molars ~45 mm apart).
    const int half = static_cast<int>(std::ceil(halfLength / step_));
    std::vector<Eigen::Vector2d> side(half + 1, Eigen::Vector2d::Zero());
    const int sub = 10;
    Eigen::Vector2d q = Eigen::Vector2d::Zero();
    for (int i = 1; i <= half; ++i) {
        for (int k = 0; k < sub; ++k) {
            const double s = ((i - 1) + (k + 0.5) / sub) * step_;
            const double theta = 1.45 * (1.0 - std::exp(-std::pow(s / (18.0 * scale), 1.5)));
            q += Eigen::Vector2d(std::cos(theta), std::sin(theta)) * (step_ / sub);
        }
        side[i] = q;
    }
    halfLength_ = half * step_;
    pts_.reserve(2 * half + 1);
    for (int i = half; i >= 1; --i) pts_.emplace_back(-side[i].x(), side[i].y());
    for (int i = 0; i <= half; ++i) pts_.push_back(side[i]);

    // Lookup grid: nearest sample per cell, by brute force once.
    Eigen::Vector2d lo = pts_[0], hi = pts_[0];
    for (const auto& p : pts_) { lo = lo.cwiseMin(p); hi = hi.cwiseMax(p); }
    const double pad = 20.0;
    cell_ = 0.5;
    gridMin_ = lo - Eigen::Vector2d::Constant(pad);
    nx_ = static_cast<int>(std::ceil((hi.x() - lo.x() + 2 * pad) / cell_)) + 1;
    ny_ = static_cast<int>(std::ceil((hi.y() - lo.y() + 2 * pad) / cell_)) + 1;
    nearest_.assign(static_cast<std::size_t>(nx_) * ny_, 0);
    tbb::parallel_for(0, ny_, [&](int j) {
        for (int i = 0; i < nx_; ++i) {
            const Eigen::Vector2d c = gridMin_ + Eigen::Vector2d(i + 0.5, j + 0.5) * cell_;
            double best = std::numeric_limits<double>::infinity();
            std::int32_t arg = 0;
            for (std::size_t k = 0; k < pts_.size(); ++k) {
                const double d = (pts_[k] - c).squaredNorm();
                if (d < best) { best = d; arg = static_cast<std::int32_t>(k); }
            }
            nearest_[static_cast<std::size_t>(j) * nx_ + i] = arg;
        }
    });
}

Vec3 Arch::point(double s) const {
    const double f = (std::clamp(s, -halfLength_, halfLength_) + halfLength_) / step_;
    const std::size_t i = std::min(static_cast<std::size_t>(f), pts_.size() - 2);
    const double t = f - static_cast<double>(i);
    const Eigen::Vector2d p = pts_[i] * (1 - t) + pts_[i + 1] * t;
    return Vec3(p.x(), p.y(), 0);
}

Vec3 Arch::distal(double s) const {
    const double f = (std::clamp(s, -halfLength_, halfLength_) + halfLength_) / step_;
    const std::size_t i = std::min(static_cast<std::size_t>(f), pts_.size() - 2);
    const Eigen::Vector2d d = (pts_[i + 1] - pts_[i]).normalized() * (s < 0 ? -1.0 : 1.0);
    return Vec3(d.x(), d.y(), 0);
}

Vec3 Arch::labial(double s) const {
    const Vec3 d = distal(s) * (s < 0 ? -1.0 : 1.0);  // direction of increasing s
    return Vec3(d.y(), -d.x(), 0);
}

ArchPosition Arch::closest(const Vec3& p) const {
    const Eigen::Vector2d q(p.x(), p.y());
    const int i = std::clamp(static_cast<int>(std::floor((q.x() - gridMin_.x()) / cell_)), 0, nx_ - 1);
    const int j = std::clamp(static_cast<int>(std::floor((q.y() - gridMin_.y()) / cell_)), 0, ny_ - 1);
    const int k0 = nearest_[static_cast<std::size_t>(j) * nx_ + i];
    const int window = 5;  // 1.25 mm of arc either side: enough within ~15 mm of the curve
    const int lo = std::max(0, k0 - window), hi = std::min(static_cast<int>(pts_.size()) - 2, k0 + window);
    double best = std::numeric_limits<double>::infinity(), bestT = 0;
    int bestK = lo;
    for (int k = lo; k <= hi; ++k) {
        const Eigen::Vector2d a = pts_[k], d = pts_[k + 1] - pts_[k];
        const double t = std::clamp((q - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
        const double dist = (q - a - d * t).squaredNorm();
        if (dist < best) { best = dist; bestK = k; bestT = t; }
    }
    const Eigen::Vector2d d = pts_[bestK + 1] - pts_[bestK];
    ArchPosition at;
    at.s = -halfLength_ + (bestK + bestT) * step_;
    at.n = (q - pts_[bestK] - d * bestT).dot(Eigen::Vector2d(d.y(), -d.x())) / d.norm();
    return at;
}

// ---------------------------------------------------------------------------------------------
// Anatomy

JawAnatomy buildJawAnatomy(Jaw jaw, int count, std::uint32_t seed) {
    if (count < 1 || count > 16)
        throw Error("phantom: the number of teeth per jaw must be 1..16, got " + std::to_string(count));
    const bool lower = jaw == Jaw::Mandible;
    const std::array<ToothKind, 8> kinds = {ToothKind::CentralIncisor, ToothKind::LateralIncisor, ToothKind::Canine,
                                            ToothKind::FirstPremolar, ToothKind::SecondPremolar, ToothKind::FirstMolar,
                                            ToothKind::SecondMolar, ToothKind::ThirdMolar};
    JawAnatomy an;
    an.jaw = jaw;
    an.mirror = !lower;
    an.bodyHeight = lower ? 27.0 : 22.0;
    an.baseExtraHalfWidth = lower ? 2.5 : 1.5;
    const double archScale = lower ? 1.0 : 1.04;

    // All 16 teeth: k = 1 (central incisor) .. 8 (third molar) on each side.
    struct Slot { int k; int unn; double side; };
    std::vector<Slot> slots;
    for (int k = 1; k <= 8; ++k) {
        // +x is the patient's left: mandible 24..17, maxilla 9..16; right: mandible 25..32, maxilla 8..1.
        slots.push_back({k, lower ? 25 - k : 8 + k, +1.0});
        slots.push_back({k, lower ? 24 + k : 9 - k, -1.0});
    }
    std::vector<ToothSpec> all;
    std::vector<std::pair<double, double>> angles;  // (labial inclination, mesial tip), degrees
    double maxEnd = 0;
    for (double side : {+1.0, -1.0}) {
        double s = kContactGapMm / 2;
        for (int k = 1; k <= 8; ++k) {
            const Slot& slot = *std::find_if(slots.begin(), slots.end(), [&](const Slot& x) { return x.k == k && x.side == side; });
            ToothSpec t = baseSpec(jaw, kinds[k - 1]);
            t.unn = slot.unn;
            scaleSpec(t, 1.0 + 0.04 * jitter(seed, t.unn, 0), 1.0 + 0.05 * jitter(seed, t.unn, 1));
            t.rootBend *= 1.0 + 0.5 * jitter(seed, t.unn, 2);
            const double inclDeg = std::atan(t.inclinationTan) / kDeg + 2.0 * jitter(seed, t.unn, 3);
            t.inclinationTan = std::tan(inclDeg * kDeg);
            angles.emplace_back(inclDeg, 2.0 + 2.0 * jitter(seed, t.unn, 4));
            t.archS = side * (s + t.halfMd);
            s += 2 * t.halfMd + kContactGapMm;
            maxEnd = std::max(maxEnd, s);
            all.push_back(t);
        }
    }
    an.arch = Arch(maxEnd + 30.0, archScale);

    for (std::size_t ti = 0; ti < all.size(); ++ti) {
        ToothSpec& t = all[ti];
        const double inclDeg = angles[ti].first, tipDeg = angles[ti].second;
        const Vec3 T = an.arch.distal(t.archS), N = an.arch.labial(t.archS), Z = Vec3::UnitZ();
        const double ai = inclDeg * kDeg, at = tipDeg * kDeg;
        Vec3 z = (std::cos(ai) * Z + std::sin(ai) * N).normalized();
        z = (z - std::tan(at) * T).normalized();
        const Vec3 y = (N - N.dot(z) * z).normalized();
        const Vec3 x = y.cross(z).dot(T) > 0 ? Vec3(y.cross(z)) : Vec3(-y.cross(z));
        t.frame.col(0) = x;
        t.frame.col(1) = y;
        t.frame.col(2) = z;
        // Junction height: the crown's bounding box stays below the occlusal plane z = 0.
        const BBox crown = transformedBox(Vec3::Zero(), t.frame, Vec3(-t.halfMd, -t.halfBl, 0),
                                          Vec3(t.halfMd, t.halfBl, t.crownHeight + 0.5));
        t.cej = an.arch.point(t.archS) + Vec3(0, 0, -kOcclusalHalfGapMm - crown.max.z());
        const double md = t.halfMd + 1.5 + std::abs(t.rootBend);
        t.box = transformedBox(t.cej, t.frame, Vec3(-md, -t.halfBl - 4.0, -t.rootLength - 1.5),
                               Vec3(md, t.halfBl + 1.5, t.crownHeight + 1.5));
    }

    // Keep the `count` teeth nearest the midline (ties: lower UNN first), in UNN order.
    std::vector<ToothSpec> kept = all;
    std::sort(kept.begin(), kept.end(), [](const ToothSpec& a, const ToothSpec& b) {
        const int ka = static_cast<int>(a.kind), kb = static_cast<int>(b.kind);
        return ka != kb ? ka < kb : a.unn < b.unn;
    });
    kept.resize(static_cast<std::size_t>(count));
    std::sort(kept.begin(), kept.end(), [](const ToothSpec& a, const ToothSpec& b) { return a.unn < b.unn; });
    an.teeth = kept;

    // The body reaches 7 mm beyond the most distal kept tooth on either side (symmetric).
    double reach = 0;
    for (const ToothSpec& t : an.teeth) reach = std::max(reach, std::abs(t.archS) + t.halfMd);
    an.boneEndS = reach + 7.0;

    // Crest and thickness tables along the arch, Gaussian-smoothed over the teeth (all 16, so the
    // crest beyond the last kept tooth continues naturally).
    const double tableHalf = an.boneEndS + 15.0;
    const double crestJitter = 0.15 * jitter(seed, 0, 5);
    for (double s = -tableHalf; s <= tableHalf + 1e-9; s += 0.5) {
        double dmin = std::numeric_limits<double>::infinity();
        for (const ToothSpec& t : all) dmin = std::min(dmin, std::pow((s - t.archS) / t.halfMd, 2));
        double W = 0, cz = 0, cs = 0, ch = 0, it = 0;
        for (const ToothSpec& t : all) {
            const double w = std::exp(-(std::pow((s - t.archS) / t.halfMd, 2) - dmin));
            W += w;
            cz += w * (t.cej.z() - kCrestBelowCejMm + crestJitter);
            cs += w * (-t.inclinationTan);
            ch += w * (t.halfBl + 1.2 + rootSpread(t));
            it += w * t.inclinationTan;
        }
        an.tableS.push_back(s);
        an.crestZ.push_back(cz / W);
        an.crestSlope.push_back(cs / W);
        an.crestHalf.push_back(ch / W);
        an.inclTan.push_back(it / W);
    }

    BBox box;
    double maxHalf = 0, maxCrest = -1e9, minCrest = 1e9;
    for (std::size_t i = 0; i < an.tableS.size(); ++i) {
        maxHalf = std::max(maxHalf, an.crestHalf[i]);
        maxCrest = std::max(maxCrest, an.crestZ[i]);
        minCrest = std::min(minCrest, an.crestZ[i]);
    }
    for (double s = -an.boneEndS; s <= an.boneEndS; s += 0.5) box.extend(an.arch.point(s));
    const double pad = maxHalf + an.baseExtraHalfWidth + 6.0;
    box.min -= Vec3(pad, pad, 0);
    box.max += Vec3(pad, pad, 0);
    box.min.z() = minCrest - an.bodyHeight - 2.0;
    box.max.z() = maxCrest + 4.0;
    an.boneBox = box;
    return an;
}

double toothField(const ToothSpec& t, const Vec3& p) {
    const Vec3 q = t.frame.transpose() * (p - t.cej);
    const double u = q.x(), v = q.y(), w = q.z();
    const double H = t.crownHeight;
    const bool multi = t.trunkLength > 0;

    // Cross-section half widths at this height: crown profile above the junction, tapering root
    // (or near-straight trunk) below it.
    double a, b, uShift = 0;
    if (w >= 0) {
        const double tt = w / H;
        a = t.halfMd * crownProfile(tt, t.cervicalMd, t.contourHeightMd, t.topMd);
        b = t.halfBl * crownProfile(tt, t.cervicalBl, t.contourHeightBl, t.topBl);
    } else {
        const double ac = t.halfMd * t.cervicalMd, bc = t.halfBl * t.cervicalBl;
        if (multi) {
            const double s = std::min(-w / t.trunkLength, 1.5);
            a = ac * (1.0 - 0.08 * s);
            b = bc * (1.0 - 0.08 * s);
        } else {
            const double s = std::min(-w / t.rootLength, 1.0);
            const double f = 1.0 - 0.72 * std::pow(s, 1.3);
            a = ac * f;
            b = bc * f;
            uShift = t.rootBend * s * s;
        }
    }
    const double n = 2.0 + (t.crossExponent - 2.0) * std::clamp((w + 1.0) / 2.0, 0.0, 1.0);
    const double au = std::abs(u - uShift) / a, av = std::abs(v) / b;
    const double r = n == 2.0 ? std::sqrt(au * au + av * av) : std::pow(std::pow(au, n) + std::pow(av, n), 1.0 / n);
    double f = (r - 1.0) * std::min(a, b);

    // Crown top: flat incisal edge, pointed canine, or cusps around a fossa.
    double top = H - t.cuspSlope * std::abs(u) - t.fossaDepth;
    for (const Cusp& c : t.cusps)
        top += c.height * std::exp(-((u - c.u) * (u - c.u) + (v - c.v) * (v - c.v)) / (c.sigma * c.sigma));
    f = smax(f, w - top, 1.0);

    if (!multi) return smax(f, -t.rootLength - w, 0.8);
    f = smax(f, -t.trunkLength - w, 1.2);
    for (const RootCone& rc : t.roots) {
        const Vec3 qs(u, v * rc.vScale, w);
        const Vec3 a0(rc.top.x(), rc.top.y() * rc.vScale, rc.top.z());
        const Vec3 a1(rc.apex.x(), rc.apex.y() * rc.vScale, rc.apex.z());
        f = smin(f, roundCone(qs, a0, a1, rc.radiusTop, rc.radiusApex), 1.0);
    }
    return f;
}

double boneField(const JawAnatomy& an, const Vec3& p) { return boneField(an, p, an.arch.closest(p)); }

double boneField(const JawAnatomy& an, const Vec3& p, const ArchPosition& at) {
    const double s = at.s, n = at.n;
    const double step = an.tableS[1] - an.tableS[0];
    const double fi = std::clamp((s - an.tableS.front()) / step, 0.0, static_cast<double>(an.tableS.size() - 1) - 1e-9);
    const std::size_t i = static_cast<std::size_t>(fi);
    const double t = fi - static_cast<double>(i);
    const std::size_t j = std::min(i + 1, an.tableS.size() - 1);
    auto lerp = [&](const std::vector<double>& v) { return v[i] * (1 - t) + v[j] * t; };
    const double crest0 = lerp(an.crestZ), crest = crest0 + lerp(an.crestSlope) * n;
    const double depth = crest0 - p.z();
    // Roots of inclined teeth lean lingually: the section follows them down to the apices.
    const double centre = -std::clamp(depth, 0.0, 16.0) * lerp(an.inclTan);
    const double half = lerp(an.crestHalf) + an.baseExtraHalfWidth * smoothstep01(depth / 12.0);
    double f = smax(std::abs(n - centre) - half, p.z() - crest, 1.2);
    f = smax(f, (crest0 - an.bodyHeight) - p.z(), 4.0);
    f = smax(f, std::abs(s) - an.boneEndS, 3.0);

    // Minus the teeth: the socket is exactly the root surface. Far teeth are culled with a lower
    // bound (distance to their box), which cannot change the result where it matters (|f| < 4).
    double teeth = std::numeric_limits<double>::infinity();
    for (const ToothSpec& tooth : an.teeth) {
        const Vec3 d = (tooth.box.min - p).cwiseMax(p - tooth.box.max).cwiseMax(0.0);
        const double boxDist = d.norm();
        teeth = std::min(teeth, boxDist > 6.0 ? boxDist : toothField(tooth, p));
    }
    return std::max(f, -teeth);
}

BBox toWorld(const JawAnatomy& an, const BBox& b) {
    if (!an.mirror) return b;
    BBox w;
    w.extend(toTemplate(an, b.min));
    w.extend(toTemplate(an, b.max));
    return w;
}

ToothAxes toothAxes(const JawAnatomy& an, const ToothSpec& t) {
    ToothAxes axes;
    const Vec3 c = t.cej + t.frame.col(2) * (t.crownHeight / 2);
    auto vec = [&](const Vec3& v) { return an.mirror ? Vec3(v.x(), v.y(), -v.z()) : v; };
    axes.crownCentre = toTemplate(an, c);
    axes.mesialDistal = vec(t.frame.col(0));
    axes.labial = vec(t.frame.col(1));
    axes.occlusal = vec(t.frame.col(2));
    return axes;
}

}  // namespace jawmesh::phantom
