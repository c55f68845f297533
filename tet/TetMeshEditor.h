// A tet mesh opened for local edits (the sliver improver's operations, tet/Sliver*.h): the tets
// around every node, which tets are still alive, which nodes may move, the add / kill / move
// edits and nested checkpoints that undo them. Killed tets stay in place until finish(), so tet
// indices are stable while editing.
#pragma once

#include "io/TetMesh.h"

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace jawmesh {

class TetMeshEditor {
public:
    /// What an open checkpoint remembers: the sizes it restores, the tets that existed before it
    /// with their score when first changed (killed or moved), and the nodes moved since, with
    /// their position before.
    struct Checkpoint {
        std::size_t firstNewTet, firstNewNode;
        std::vector<std::pair<std::int32_t, double>> changedTets;
        std::vector<std::pair<std::int32_t, Vec3>> movedNodes;
    };

    /// Opens `mesh` (positively oriented tets) for editing in place. Nodes on an interface (a face
    /// between two labels) or on the mesh boundary are fixed. Cost: O(T log T) (the face adjacency).
    explicit TetMeshEditor(TetMesh& mesh);

    const Vec3& node(std::int32_t v) const { return mesh_.nodes[std::size_t(v)]; }
    const std::vector<Vec3>& nodes() const { return mesh_.nodes; }
    const Tet& tet(std::int32_t t) const { return mesh_.tets[std::size_t(t)]; }
    Label label(std::int32_t t) const { return mesh_.labels[std::size_t(t)]; }
    bool alive(std::int32_t t) const { return alive_[std::size_t(t)] != 0; }
    /// On an interface or the mesh boundary: smoothing never moves it.
    bool fixed(std::int32_t v) const { return fixed_[std::size_t(v)] != 0; }
    /// The alive tets around node v.
    const std::vector<std::int32_t>& star(std::int32_t v) const { return star_[std::size_t(v)]; }
    /// Tets made so far, killed ones included (indices below this are valid).
    std::size_t tetCount() const { return mesh_.tets.size(); }
    std::size_t nodeCount() const { return mesh_.nodes.size(); }

    /// The tet's sliverScore (tet/SliverScore.h).
    double score(std::int32_t t) const;
    double volume(std::int32_t t) const;
    /// Whether the tets `fresh` fill exactly the volume of the tets `old` (a re-triangulation of
    /// the same cavity; with nearly flat tets around, positive orientation alone does not prove it).
    bool fillsSameVolume(const std::vector<std::int32_t>& old, const std::vector<Tet>& fresh) const;

    /// Face k of t (the three nodes other than t[k]) and the tet on its other side, whatever its
    /// label (-1: the mesh boundary).
    std::int32_t acrossFace(std::int32_t t, int k, std::int32_t f[3]) const;
    /// Face k of t and the tet on its other side when that tet has t's label (-1 otherwise: an
    /// interface, the outside).
    std::int32_t sameRegionNeighbour(std::int32_t t, int k, std::int32_t f[3]) const;
    /// The tets around edge (a, b).
    std::vector<std::int32_t> tetsWith(std::int32_t a, std::int32_t b) const;
    /// The ring of edge (a, b) when it lies inside one region: its tets (all of label `label`,
    /// every face around the edge shared by two of them); empty otherwise.
    std::vector<std::int32_t> interiorRing(std::int32_t a, std::int32_t b, Label label) const;
    /// Whether v lies on the mesh's outer boundary (a face of a tet around it has no tet across).
    bool onMeshBoundary(std::int32_t v) const;

    void add(const Tet& e, Label label);
    void kill(std::int32_t t);
    /// Kills every tet of `old`, then adds every tet of `fresh` with `label`.
    void replace(const std::vector<std::int32_t>& old, const std::vector<Tet>& fresh, Label label);
    /// Moves node v (which the open checkpoints remember).
    void move(std::int32_t v, const Vec3& p);
    /// Appends a node no tet uses yet; place it with placeNewNode, drop it with dropNewNode or
    /// use it in added tets.
    std::int32_t addNode(const Vec3& p, bool fixed);
    /// Places the node addNode returned last, while no tet uses it.
    void placeNewNode(const Vec3& p) { mesh_.nodes.back() = p; }
    /// Removes the node addNode returned last, which no tet uses.
    void dropNewNode();

    /// Opens a checkpoint (checkpoints nest); every edit until it is closed can be undone.
    void checkpoint();
    /// Closes the innermost checkpoint keeping its edits (the enclosing ones still know them).
    void keep();
    /// Closes the innermost checkpoint restoring the mesh as it was when it was opened.
    void rollback();
    /// The innermost open checkpoint.
    const Checkpoint& innermost() const { return checkpoints_.back(); }

    /// Writes the alive tets back into the mesh; the nodes that no alive tet uses (an edit took
    /// their last tets) are dropped, the others keep their order. The editor is done.
    void finish();

    /// The tets added, or with a node moved (rollbacks included), since takeTouched was last
    /// called, repeats and tets gone since included: only these can have a new score.
    std::vector<std::int32_t> takeTouched() { return std::exchange(touched_, {}); }

private:
    /// For every open checkpoint: remembers the score of a tet that existed before it, the first
    /// time it changes.
    void recordChange(std::int32_t t);

    TetMesh& mesh_;
    std::vector<char> alive_, fixed_;
    std::vector<std::vector<std::int32_t>> star_;
    std::vector<Checkpoint> checkpoints_;  ///< open ones, innermost last
    std::vector<std::int32_t> touched_;    ///< takeTouched
};

}  // namespace jawmesh
