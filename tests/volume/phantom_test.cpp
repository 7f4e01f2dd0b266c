#include "lw/core/error.h"
#include "lw/volume/phantom.h"

#include <cstdlib>
#include <cstring>
#include <gtest/gtest.h>
#include <memory>
#include <string>
#include <vector>

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

TEST(Phantom, ReportsEverySliceInOrderAndKeepsItsVoxels) {
    std::vector<double> fractions;
    std::vector<std::string> messages;
    core::Progress progress([&](double fraction, const std::string& message) {
        fractions.push_back(fraction);
        messages.push_back(message);
    });
    const glm::ivec3 dims(24, 20, 40);
    const volume::Volume reported = makePhantom(dims, PhantomKind::Ct, 0, {}, &progress);
    const volume::Volume quiet = makePhantom(dims, PhantomKind::Ct);
    ASSERT_EQ(fractions.size(), std::size_t(dims.z)); // 40 slices: every step a new per-mille
    for (std::size_t i = 0; i < fractions.size(); ++i) {
        EXPECT_DOUBLE_EQ(fractions[i], double(i + 1) / dims.z);
        EXPECT_EQ(messages[i], "Generating the phantom");
    }
    EXPECT_EQ(std::memcmp(reported.data(), quiet.data(), quiet.byteSize()), 0);
}

TEST(Phantom, CancelledTokenGeneratesNoSlice) {
    auto token = std::make_shared<core::CancelToken>();
    token->cancel();
    int steps = 0;
    core::Progress progress([&](double, const std::string&) { ++steps; }, token);
    EXPECT_THROW(makePhantom({16, 16, 32}, PhantomKind::Ct, 0, {}, &progress), core::Cancelled);
    EXPECT_EQ(steps, 0);
}

// One thread makes the order deterministic: the token is cancelled in the callback of the
// quarter's slice, and the next slice is the first not generated.
TEST(Phantom, CancelWhileGeneratingStopsAtTheNextSlice) {
    auto token = std::make_shared<core::CancelToken>();
    int steps = 0;
    core::Progress progress(
        [&](double fraction, const std::string&) {
            ++steps;
            if (fraction >= 0.25)
                token->cancel();
        },
        token);
    EXPECT_THROW(makePhantom({16, 16, 64}, PhantomKind::Sphere, 1, {}, &progress), core::Cancelled);
    EXPECT_EQ(steps, 16);
}

TEST(Phantom, RejectsBadInput) {
    EXPECT_THROW(parsePhantomKind("cube"), core::Error);
    EXPECT_THROW(makePhantom({0, 4, 4}, PhantomKind::Ct), core::Error);
}

} // namespace
} // namespace lw::volume
