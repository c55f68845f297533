// Region labels: the numbering scheme (bone, tooth 100 + UNN, PDL 200 + UNN), names and kinds, and the
// refusal of numbers that are no tooth of a jaw.
#include "io/Error.h"
#include "io/Labels.h"

#include <gtest/gtest.h>

using namespace jawmesh;

TEST(Labels, ToothAndPdlLabelsRoundTrip) {
    for (int unn = 1; unn <= 32; ++unn) {
        EXPECT_EQ(labelKind(toothLabel(unn)), LabelKind::Tooth);
        EXPECT_EQ(labelKind(pdlLabel(unn)), LabelKind::Pdl);
        EXPECT_EQ(labelUnn(toothLabel(unn)), unn);
        EXPECT_EQ(labelUnn(pdlLabel(unn)), unn);
    }
    EXPECT_EQ(toothLabel(24), 124);
    EXPECT_EQ(pdlLabel(24), 224);
    EXPECT_EQ(labelName(toothLabel(24)), "tooth_24");
    EXPECT_EQ(labelName(pdlLabel(7)), "pdl_7");
    EXPECT_EQ(labelName(boneLabel(Jaw::Mandible)), "bone_mandible");
    EXPECT_EQ(labelName(boneLabel(Jaw::Maxilla)), "bone_maxilla");
}

TEST(Labels, RejectsInvalidNumbers) {
    EXPECT_THROW(toothLabel(0), Error);
    EXPECT_THROW(pdlLabel(33), Error);
    EXPECT_THROW(labelKind(99), Error);
    EXPECT_THROW(labelUnn(kMandibleBoneLabel), Error);
    EXPECT_THROW(jawFromName("skull"), Error);
}

TEST(Labels, JawOfTooth) {
    EXPECT_EQ(jawOfTooth(1), Jaw::Maxilla);
    EXPECT_EQ(jawOfTooth(16), Jaw::Maxilla);
    EXPECT_EQ(jawOfTooth(17), Jaw::Mandible);
    EXPECT_EQ(jawOfTooth(32), Jaw::Mandible);
}
