// Staged multi-file outputs (io/StagedFolder.h): nothing reaches the destination before commit();
// an abandoned staging leaves no trace, not even the parent folders it had to create.
#include "io/AtomicFile.h"
#include "io/StagedFolder.h"
#include "support/TestData.h"
#include "io/IoTestUtil.h"

namespace jawmesh::test {
namespace {
namespace fs = std::filesystem;

void writeAtomicText(const std::string& path, const std::string& text) {
    writeFileAtomically(path, [&](std::ostream& out) { out << text; }, false);
}

std::size_t entriesIn(const fs::path& dir) {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

TEST(StagedFolder, NothingArrivesBeforeCommitAndAllAtOnceAfter) {
    const fs::path root = scratchDir("staged-new");
    const fs::path dest = root / "out" / "mandible";
    {
        StagedFolder staged(dest.string());
        EXPECT_NE(staged.path().find(".mandible.partial-"), std::string::npos) << staged.path();
        writeAtomicText(staged.path() + "/a.txt", "a");
        writeAtomicText(staged.path() + "/sub/b.txt", "b");
        EXPECT_FALSE(fs::exists(dest));
        staged.commit(StagedFolder::Mode::Replace);
    }
    EXPECT_EQ(readBytes(dest / "a.txt"), "a");
    EXPECT_EQ(readBytes(dest / "sub" / "b.txt"), "b");
    EXPECT_EQ(entriesIn(root / "out"), 1u) << "the staging folder is gone";
}

TEST(StagedFolder, AbandonedStagingLeavesNothingNotEvenCreatedParents) {
    const fs::path root = scratchDir("staged-abandon");
    try {
        StagedFolder staged((root / "new" / "deeper" / "mandible").string());
        writeAtomicText(staged.path() + "/a.txt", "a");
        throw Error("a stage failed");
    } catch (const Error&) {
    }
    EXPECT_EQ(entriesIn(root), 0u) << "root/new was created for the staging and must be gone";
}

TEST(StagedFolder, ReplaceDropsOldFilesMergeKeepsThem) {
    const fs::path root = scratchDir("staged-modes");
    const fs::path dest = root / "jaw";
    writeAtomicText((dest / "old.txt").string(), "old");
    writeAtomicText((dest / "same.txt").string(), "before");
    {
        StagedFolder staged(dest.string());
        writeAtomicText(staged.path() + "/same.txt", "after");
        staged.commit(StagedFolder::Mode::Merge);
    }
    EXPECT_EQ(readBytes(dest / "old.txt"), "old");
    EXPECT_EQ(readBytes(dest / "same.txt"), "after");
    {
        StagedFolder staged(dest.string());
        writeAtomicText(staged.path() + "/new.txt", "new");
        staged.commit(StagedFolder::Mode::Replace);
    }
    EXPECT_FALSE(fs::exists(dest / "old.txt"));
    EXPECT_EQ(readBytes(dest / "new.txt"), "new");
    EXPECT_EQ(entriesIn(root), 1u) << "no staging or .old folder left";
}

TEST(StagedFolder, RefusesADestinationWithoutAName) {
    EXPECT_THROW(StagedFolder("/"), Error);
}

}  // namespace
}  // namespace jawmesh::test
