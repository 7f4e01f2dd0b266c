// The thick-slice field made on the CUDA device against the host's (label gpu: runs only where a
// CUDA device is present, SKIP elsewhere): the same int16 copy, bit for bit, with the same
// geometry and value mapping -- over every voxel type, sizes off the 32 x 8 pixel blocks, a
// gantry-tilted stack with uneven gaps, refinement in-plane as well as along the slices, and
// iso-values where whole slices have no contour; the faces' maxima found on the device are the
// host's; the page lock of the kept copies.

#include "filled_volume.h"
#include "lw/core/error.h"
#include "lw/kernels/cpu/border_cap_cpu.h"
#include "lw/kernels/cuda/page_locked_host.h"
#include "lw/render/aabb.h"
#include "lw/render/camera.h"
#include "lw/render/renderer_factory.h"
#include "lw/render/surface_sampling.h"
#include "lw/volume/phantom.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <gtest/gtest.h>
#include <random>
#include <string>
#include <vector>

namespace lw::render {
namespace {

using volume::Volume;
using volume::VolumeGeometry;

struct Case {
    std::string name;
    std::function<Volume()> make;
    std::vector<double> isos;
    bool bridgesThinWalls = false; // the case's thin walls slide between slices (checked)
};

// The CT phantom's voxels on thick slices (0.5 mm pixels, 3 mm slices).
Volume thickPhantom() {
    const Volume thin = volume::makePhantom({100, 67, 45}, volume::PhantomKind::Ct);
    Volume thick(thin.dims(), thin.voxelType(),
                 VolumeGeometry::regular({-20.0, 10.0, 5.0}, {0.5, 0.5, 3.0}));
    std::memcpy(thick.data(), thin.data(), thin.byteSize());
    thick.setValueMapping(thin.valueMapping());
    return thick;
}

// A sphere on a gantry-tilted stack (20 degrees) with gaps of 2 and 3.5 mm, float voxels.
Volume tiltedUnevenSphere() {
    const double tilt = 20.0 * 3.14159265358979323846 / 180.0;
    std::vector<glm::dvec3> slices;
    double z = 0.0;
    for (int k = 0; k < 23; ++k) {
        slices.push_back({0.0, z * std::tan(tilt), z});
        z += (k % 2 == 0) ? 2.0 : 3.5;
    }
    const auto geometry =
        VolumeGeometry::fromSlicePositions({1, 0, 0}, {0, 1, 0}, 0.45, 0.6, slices);
    const glm::dvec3 centre = geometry.indexToPatient({41.0, 38.0, 11.0});
    return lw::test::makeFilledVolume<float>(
        {83, 71, 23},
        [&](int x, int y, int k) {
            return 25.0 -
                   glm::length(geometry.indexToPatient({double(x), double(y), double(k)}) - centre);
        },
        geometry);
}

// A thin spherical shell (2 mm, radius 30 mm) on 4 mm slices: near its poles the cuts of
// neighbouring slices lie side by side, where the thin-wall pass slides them together.
Volume thinShellOnThickSlices() {
    return lw::test::makeFilledVolume<std::int16_t>(
        {140, 130, 19},
        [&](int x, int y, int k) {
            const double r =
                glm::length(glm::dvec3(x * 0.5 - 35.0, y * 0.5 - 32.0, k * 4.0 - 36.0));
            return std::lround(1000.0 * std::clamp(1.0 - std::abs(r - 30.0), 0.0, 1.0));
        },
        VolumeGeometry::regular({0.0, 0.0, 0.0}, {0.5, 0.5, 4.0}));
}

// A 3 mm shell around a wavy sphere, with noise, on very thick slices of fine pixels: the
// distance limit (a slice step) reaches 33 pixels at 0.25 mm pixels and 8 mm slices, 84 at
// 0.12 mm and 10 mm -- windows wider than a block of 32 pixels, where the device's search must
// still find every crossing the host's scans find. Sizes off the blocks.
Volume shellOnFinePixels(glm::ivec3 dims, double pixelMm, double sliceMm) {
    std::mt19937 random(7);
    std::uniform_int_distribution<int> noise(-40, 40);
    const glm::dvec3 centre(dims.x * pixelMm / 2.0, dims.y * pixelMm / 2.0,
                            (dims.z - 1) * sliceMm / 2.0);
    const double radius = 0.38 * std::min(dims.x, dims.y) * pixelMm;
    return lw::test::makeFilledVolume<std::int16_t>(
        dims,
        [&](int x, int y, int k) {
            const glm::dvec3 p = glm::dvec3(x * pixelMm, y * pixelMm, k * sliceMm) - centre;
            const double wavy = radius + 0.6 * std::sin(3.0 * std::atan2(p.y, p.x));
            const double wall = std::clamp(1.5 - std::abs(glm::length(p) - wavy), 0.0, 1.0);
            return std::lround(1000.0 * wall) + noise(random);
        },
        VolumeGeometry::regular({0.0, 0.0, 0.0}, {pixelMm, pixelMm, sliceMm}));
}

// Coarse noise of type T on coarse pixels, so that the refinement splits rows and columns too.
template <typename T> Volume coarseNoise(glm::ivec3 dims, glm::dvec3 spacing, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_int_distribution<int> value(0, 200);
    return lw::test::makeFilledVolume<T>(
        dims, [&](int, int, int) { return value(random); },
        VolumeGeometry::regular({0.0, 0.0, 0.0}, spacing));
}

std::vector<Case> cases() {
    return {
        {"phantom int16 on 3 mm slices", thickPhantom, {300.5, -500.0, 5000.0}},
        {"tilted uneven float sphere", tiltedUnevenSphere, {0.0, 12.5}},
        {"thin shell on 4 mm slices", thinShellOnThickSlices, {300.0}, true},
        {"uint8 noise refined in plane",
         [] {
             return coarseNoise<std::uint8_t>({40, 23, 19}, {3.0, 3.0, 12.0}, 1);
         },
         {100.0, 150.5}},
        {"shell on 8 mm slices of 0.25 mm pixels",
         [] {
             return shellOnFinePixels({150, 141, 7}, 0.25, 8.0);
         },
         {400.0, 0.5}},
        {"shell on 10 mm slices of 0.12 mm pixels",
         [] {
             return shellOnFinePixels({205, 97, 4}, 0.12, 10.0);
         },
         {400.0}},
        {"uint16 noise 33x9x5",
         [] {
             return coarseNoise<std::uint16_t>({33, 9, 5}, {0.8, 0.8, 4.0}, 2);
         },
         {120.0}},
    };
}

std::string caseName(const testing::TestParamInfo<Case>& info) {
    std::string name;
    for (char c : info.param.name)
        name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    return name;
}

class ThickSlicesOnDevice : public testing::TestWithParam<Case> {
protected:
    void SetUp() override {
        if (!cudaAvailability().available)
            GTEST_SKIP() << "no CUDA device: " << cudaAvailability().reason;
    }
};

TEST_P(ThickSlicesOnDevice, MakesTheHostsFieldBitForBit) {
    const auto source = std::make_shared<const Volume>(GetParam().make());
    const VolumeSampling sampling{Oversampling::Auto, ThickSlices::Smooth};
    ASSERT_TRUE(samplingPlan(source->dims(), source->geometry(), sampling).shapeBased)
        << "the case must have thick slices";
    DrawnVolumeMaker device(source, Backend::Cuda);
    for (const double iso : GetParam().isos) {
        const std::string where = GetParam().name + " at " + std::to_string(iso);
        const auto onDevice = device.make(sampling, iso, 1);
        ASSERT_TRUE(device.lastMadeOnDevice()) << where << ": " << device.takeNote();
        const auto onHost = volumeToRender(source, sampling, iso, 2);
        if (GetParam().bridgesThinWalls) {
            VolumeSampling pointwise = sampling;
            pointwise.thinWallMm = 0.0;
            const auto unbridged = volumeToRender(source, pointwise, iso, 2);
            EXPECT_FALSE(std::equal(onHost->dataAs<std::int16_t>(),
                                    onHost->dataAs<std::int16_t>() + onHost->voxelCount(),
                                    unbridged->dataAs<std::int16_t>()))
                << where << ": the thin walls were not slid";
        }
        ASSERT_EQ(onDevice->dims(), onHost->dims()) << where;
        ASSERT_EQ(onDevice->voxelType(), onHost->voxelType()) << where;
        EXPECT_EQ(onDevice->valueMapping().slope, onHost->valueMapping().slope) << where;
        EXPECT_EQ(onDevice->valueMapping().intercept, onHost->valueMapping().intercept) << where;
        EXPECT_EQ(onDevice->geometry().indexToPatient({1.0, 2.0, 3.0}),
                  onHost->geometry().indexToPatient({1.0, 2.0, 3.0}))
            << where;
        const std::int16_t* a = onDevice->dataAs<std::int16_t>();
        const std::int16_t* b = onHost->dataAs<std::int16_t>();
        std::size_t differing = 0, first = 0;
        for (std::size_t v = onDevice->voxelCount(); v-- > 0;)
            if (a[v] != b[v]) {
                ++differing;
                first = v;
            }
        EXPECT_EQ(differing, 0u) << where << ": first at voxel " << first << " (device "
                                 << (differing ? a[first] : 0) << ", host "
                                 << (differing ? b[first] : 0) << ")";
        const DeviceVoxelCopy copy = device.deviceCopy();
        ASSERT_TRUE(copy.faceMaxima.has_value()) << where;
        EXPECT_EQ(*copy.faceMaxima, kernels::cpu::borderFaceMaxima(*onHost).value) << where;
    }
}

INSTANTIATE_TEST_SUITE_P(Volumes, ThickSlicesOnDevice, testing::ValuesIn(cases()), caseName);

// The device path's host copies are written again once nobody holds them, never while someone
// does: a copy held across later iso-values keeps its own, and a released one's memory comes
// back for the next.
TEST(ThickSlicesOnDeviceCopies, AHeldCopyKeepsItsVoxelsAndAFreeOneIsWrittenAgain) {
    if (!cudaAvailability().available)
        GTEST_SKIP() << "no CUDA device: " << cudaAvailability().reason;
    const auto source = std::make_shared<const Volume>(thickPhantom());
    const VolumeSampling sampling{Oversampling::Auto, ThickSlices::Smooth};
    DrawnVolumeMaker maker(source, Backend::Cuda);
    const auto sameVoxels = [](const Volume& a, const Volume& b) {
        return a.dims() == b.dims() && std::memcmp(a.data(), b.data(), a.byteSize()) == 0;
    };
    const auto held = maker.make(sampling, 300.5, 1);
    ASSERT_TRUE(maker.lastMadeOnDevice()) << maker.takeNote();
    const void* heldVoxels = held->data();
    const void* releasedVoxels = nullptr;
    for (const double iso : {-400.0, 700.5, 100.0}) {
        auto next = maker.make(sampling, iso, 1);
        EXPECT_NE(next->data(), heldVoxels) << iso << ": a held copy was written again";
        EXPECT_TRUE(sameVoxels(*next, *volumeToRender(source, sampling, iso, 2))) << iso;
        EXPECT_EQ(next->valueMapping().intercept, iso);
        releasedVoxels = next->data();
    } // each `next` is released here: the next iso-value may write it again
    EXPECT_TRUE(sameVoxels(*held, *volumeToRender(source, sampling, 300.5, 2)));
    EXPECT_EQ(held->valueMapping().intercept, 300.5);
    const auto reused = maker.make(sampling, 500.5, 1);
    EXPECT_EQ(reused->data(), releasedVoxels) << "a released copy's memory is written again";
    EXPECT_TRUE(sameVoxels(*reused, *volumeToRender(source, sampling, 500.5, 2)));
}

// The renderers of a copy made on the device take its voxels from there, device to device: bound
// to a host volume that holds no surface at all, with the device copy beside it, each CUDA
// renderer draws what it draws of the copy's own host voxels -- so it read the device's.
class RenderersOnTheDeviceCopy : public testing::TestWithParam<SilhouetteMethod> {
protected:
    void SetUp() override {
        if (!cudaAvailability().available)
            GTEST_SKIP() << "no CUDA device: " << cudaAvailability().reason;
    }
};

PixelMask drawnLines(SilhouetteRenderer& renderer, const Volume& volume, double iso) {
    CameraSetup setup;
    setup.bounds = volumeBounds(volume);
    setup.azimuthDeg = 40.0;
    setup.elevationDeg = 20.0;
    SilhouetteSettings settings;
    settings.isoReal = iso;
    settings.closeAtBorder = false; // the border cap comes from the host's voxels
    return renderer.render(Camera(setup, 160, 120), settings).lines;
}

TEST_P(RenderersOnTheDeviceCopy, ReadTheDevicesVoxelsNotTheHosts) {
    const auto source = std::make_shared<const Volume>(thickPhantom());
    const VolumeSampling sampling{Oversampling::Auto, ThickSlices::Smooth};
    DrawnVolumeMaker maker(source, Backend::Cuda);
    constexpr double kIso = 300.5;
    const auto field = maker.make(sampling, kIso, 1);
    ASSERT_TRUE(maker.lastMadeOnDevice()) << maker.takeNote();
    ASSERT_NE(maker.deviceCopy().voxels, nullptr);
    // All voxels 0: every point at the iso-value, inside, so no surface is left to draw.
    Volume blank(field->dims(), field->voxelType(), field->geometry());
    std::memset(blank.data(), 0, blank.byteSize()); // a new volume's voxels are not initialised
    blank.setValueMapping(field->valueMapping());

    std::unique_ptr<SilhouetteRenderer> fromDevice, fromHost, ofBlank;
    try {
        fromDevice = createSilhouetteRenderer(GetParam(), Backend::Cuda);
        fromHost = createSilhouetteRenderer(GetParam(), Backend::Cuda);
        ofBlank = createSilhouetteRenderer(GetParam(), Backend::Cuda);
    } catch (const core::Error& error) {
        GTEST_SKIP() << "no CUDA renderer of this method here: " << error.what();
    }
    fromDevice->setVolumeWithDeviceCopy(blank, maker.deviceCopy());
    fromHost->setVolume(*field);
    ofBlank->setVolume(blank);
    const PixelMask reference = drawnLines(*fromHost, *field, kIso);
    EXPECT_GT(reference.count(), 100u) << "the copy's lines";
    EXPECT_EQ(drawnLines(*ofBlank, blank, kIso).count(), 0u) << "the blank volume draws nothing";
    EXPECT_TRUE(drawnLines(*fromDevice, blank, kIso) == reference)
        << "bound with the device copy, the renderer draws the copy";
}

INSTANTIATE_TEST_SUITE_P(Methods, RenderersOnTheDeviceCopy,
                         testing::Values(SilhouetteMethod::GeometryShader,
                                         SilhouetteMethod::RayCastVisibility,
                                         SilhouetteMethod::ZBuffer),
                         [](const testing::TestParamInfo<SilhouetteMethod>& info) {
                             return "Method" + std::to_string(int(info.param));
                         });

// The kept copies' page lock: a range is locked once (a second lock of the same pages is
// refused and leaves the first alone), the lock moves with its object and ends with it.
TEST(PageLockedHostRange, LocksOnceMovesAndUnlocks) {
    if (!cudaAvailability().available)
        GTEST_SKIP() << "no CUDA device: " << cudaAvailability().reason;
    std::vector<std::int16_t> memory(std::size_t(1) << 20);
    kernels::cuda::PageLockedHostRange first;
    ASSERT_TRUE(first.lock(memory.data(), memory.size() * sizeof(std::int16_t)).ok());
    EXPECT_TRUE(first.locked());
    kernels::cuda::PageLockedHostRange second;
    EXPECT_FALSE(second.lock(memory.data(), memory.size() * sizeof(std::int16_t)).ok());
    EXPECT_FALSE(second.locked());
    kernels::cuda::PageLockedHostRange moved = std::move(first);
    EXPECT_FALSE(first.locked());
    EXPECT_TRUE(moved.locked());
    moved.unlock();
    EXPECT_FALSE(moved.locked());
    // Unlocked, the pages may be locked again.
    EXPECT_TRUE(second.lock(memory.data(), memory.size() * sizeof(std::int16_t)).ok());
}

// On the CPU back-end the maker is the host's volumeToRender.
TEST(ThickSlicesOnHost, TheCpuBackendMakesTheFieldOnTheHost) {
    const auto source = std::make_shared<const Volume>(thickPhantom());
    DrawnVolumeMaker host(source, Backend::Cpu);
    const VolumeSampling sampling{Oversampling::Auto, ThickSlices::Smooth};
    const auto made = host.make(sampling, 300.5, 1);
    EXPECT_FALSE(host.lastMadeOnDevice());
    EXPECT_EQ(host.deviceCopy().voxels, nullptr);
    const auto reference = volumeToRender(source, sampling, 300.5, 1);
    ASSERT_EQ(made->dims(), reference->dims());
    EXPECT_EQ(std::memcmp(made->data(), reference->data(), made->byteSize()), 0);
}

} // namespace
} // namespace lw::render
