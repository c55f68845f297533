// How the sliver improver (tet/ImproveSlivers.h) rates tets and decides: a tet's score (minus the
// cosine of its smallest dihedral angle), the objective of a set of tets (worst score and shortfall
// below the target) and the acceptance rule an operation applies to each candidate it could make.
#pragma once

#include "tet/ElementQuality.h"

#include "io/Angles.h"
#include "io/TetMesh.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace jawmesh {

constexpr double kInvalidScore = -3.0;  ///< below every cosine-based score: an inverted or flat tet

/// The score below from a tet's four face normals n (all outward or all inward) and their
/// lengths len (> 0).
inline double scoreOfFaceNormals(const Vec3 (&n)[4], const double (&len)[4]) {
    double worstCos = -1.0;  // cosine of the interior dihedral angle = -cos(angle of outward normals)
    for (int k = 0; k < 4; ++k)
        for (int l = k + 1; l < 4; ++l) worstCos = std::max(worstCos, -n[k].dot(n[l]) / (len[k] * len[l]));
    return -worstCos;
}

/// Score of a tet: minus the cosine of its smallest interior dihedral angle (monotone in that
/// angle, cheaper than the angle itself); kInvalidScore when not positively oriented.
inline double sliverScore(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    const Vec3 u = b - a, v = c - a, w = d - a;
    if (!(u.dot(v.cross(w)) > 0)) return kInvalidScore;
    const Vec3 n[4] = {(c - b).cross(d - b), (d - a).cross(c - a), (b - a).cross(d - a), (c - a).cross(b - a)};
    double len[4];
    for (int k = 0; k < 4; ++k) {
        len[k] = n[k].norm();
        if (!(len[k] > 0)) return kInvalidScore;
    }
    return scoreOfFaceNormals(n, len);
}

/// The smallest dihedral angle, degrees, of a tet of score s (0 for an invalid tet).
inline double scoreToDeg(double s) { return s <= kInvalidScore ? 0.0 : degrees(std::acos(std::clamp(-s, -1.0, 1.0))); }

/// The score a tet of smallest dihedral angle `deg` has.
inline double degToScore(double deg) { return -std::cos(radians(deg)); }

/// What a local operation optimises over the tets it changes: the worst score and the total
/// shortfall below the target (so a bad tet next to a worse one that no operation can fix is
/// still improved).
struct Objective {
    double worst = std::numeric_limits<double>::infinity();
    double deficit = 0;
    void add(double s, double target) {
        worst = std::min(worst, s);
        deficit += std::max(0.0, target - s);
    }
    /// Better when neither the worst score nor the shortfall gets worse and one of them improves
    /// (Pareto). Trading one for the other lets the improver churn: raising the worst tet of a
    /// star while pushing several good ones under the target (the shared mandible: 260 tets left
    /// under 10 degrees that way, 62 with this rule, from TetGen's 27,619).
    bool betterThan(const Objective& o) const {
        if (worst < o.worst - kTie || deficit > o.deficit + kTie) return false;
        return worst > o.worst + 1e-9 || deficit < o.deficit - 1e-9;
    }
    /// Worse than everything: betterThan nothing, and no partial objective is worse than it.
    static Objective hopeless() { return {-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()}; }
    /// A bound no objective can pass and still win against this one after a chain of `steps`
    /// betterThan comparisons (each may give up kTie in either part).
    Objective hopelessBelow(std::size_t steps) const {
        const double slack = 2.0 * kTie * double(steps + 1);
        return {worst - slack, deficit + slack};
    }

private:
    static constexpr double kTie = 1e-12;  ///< below rounding of a score or a shortfall: not worse
};

/// The rule an operation applies to each candidate it could make, given the objective `after` of
/// the tets it would make and `before` of those they replace. Hill climbing accepts a candidate
/// only when it is betterThan what it replaces; the lookahead (tet/ImproveSlivers.cpp) forces the
/// k-th candidate whether it helps or not, and counts the candidates so it knows when an operation
/// has no more. It also carries the target score the objectives' shortfall is measured from.
class Acceptance {
public:
    /// Candidates that make the objective betterThan before (the hill climbing).
    static Acceptance improving(double target) { return Acceptance(target, -1); }
    /// Exactly the k-th candidate (from 0) that makes no tet flatter than 1 degree, or than the
    /// worst it replaces: a nearly flat tet's orientation is at the mercy of rounding, and the
    /// operations after it rely on it.
    static Acceptance forced(double target, int k) { return Acceptance(target, k); }

    /// The score below which a tet counts as bad (its shortfall adds to an objective's deficit).
    double target() const { return target_; }
    /// Whether to make the candidate; a forced rule counts every candidate that passes its floor.
    bool operator()(const Objective& after, const Objective& before) {
        if (forced_ < 0) return after.betterThan(before);
        static const double floor = -std::cos(M_PI / 180.0);
        return after.worst > std::min(before.worst, floor) && seen_++ == forced_;
    }
    /// Candidates a forced rule has seen so far (fewer than k + 1: there was no k-th).
    int candidatesSeen() const { return seen_; }

private:
    Acceptance(double target, int forced) : target_(target), forced_(forced) {}
    double target_;
    int forced_;
    int seen_ = 0;
};

}  // namespace jawmesh
