#include "lw/core/error.h"
#include "lw/volume/phantom.h"

#include <cstdlib>
#include <cstring>
#include <gtest/gtest.h>

namespace lw::volume {
namespace {

// phantom.py allows +-1 per voxel (float32 exp/sin/cos may round differently from numpy), so
// the sum may differ by at most the voxel count. The count above 300.5 changes only where a
// voxel sits at 300 or 301 and rounds differently: we allow 0.1% of the count.
void expectChecksum(glm::ivec3 dims, PhantomKind kind, std::int64_t sum, std::int64_t above) {
    const volume::Volume phantom = makePhantom(dims, kind);
    const PhantomChecksum c = phantomChecksum(phantom);
    const auto voxels = std::int64_t(phantom.voxelCount());
    EXPECT_LE(std::llabs(c.sum - sum), voxels) << "sum " << c.sum << " vs phantom.py " << sum;
    EXPECT_LE(std::llabs(c.above - above), above / 1000)
        << "above " << c.above << " vs phantom.py " << above;
}

TEST(Phantom, ChecksumsMatchPhantomPy) {
    expectChecksum(glm::ivec3(64), PhantomKind::Ct, -180886926, 12625);
    expectChecksum(glm::ivec3(128), PhantomKind::Ct, -1431683672, 103593);
    expectChecksum(glm::ivec3(64), PhantomKind::Sphere, -205561911, 27400);
}

TEST(Phantom, VolumeHasGeometryAndType) {
    const volume::Volume phantom = makePhantom({20, 16, 12}, PhantomKind::Sphere);
    EXPECT_EQ(phantom.voxelType(), volume::VoxelType::Int16);
    EXPECT_EQ(phantom.dims(), glm::ivec3(20, 16, 12));
    EXPECT_DOUBLE_EQ(phantom.geometry().spacingI(), 1.0);
    // Centred on the patient origin.
    const glm::dvec3 centre = phantom.geometry().indexToPatient({9.5, 7.5, 5.5});
    EXPECT_NEAR(glm::length(centre), 0.0, 1e-12);
    EXPECT_TRUE(phantom.valueMapping().isIdentity());
}

TEST(Phantom, ThreadCountDoesNotChangeVoxels) {
    const volume::Volume a = makePhantom({33, 29, 31}, PhantomKind::Ct, 1);
    const volume::Volume b = makePhantom({33, 29, 31}, PhantomKind::Ct, 0);
    ASSERT_EQ(a.byteSize(), b.byteSize());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.byteSize()), 0);
}

TEST(Phantom, RejectsBadInput) {
    EXPECT_THROW(parsePhantomKind("cube"), core::Error);
    EXPECT_THROW(makePhantom({0, 4, 4}, PhantomKind::Ct), core::Error);
}

} // namespace
} // namespace lw::volume
