#pragma once

// What the review frame's tests share: a small CT phantom, its cameras and requests, and how
// pictures are compared.

#include "lw/render/review_frame.h"
#include "lw/volume/phantom.h"

#include <cstdlib>
#include <cstring>
#include <gtest/gtest.h>
#include <memory>

namespace lw::render::test {

constexpr double kIso = 300.5;

inline std::shared_ptr<const volume::Volume> phantom() {
    return std::make_shared<const volume::Volume>(
        volume::makePhantom({72, 64, 56}, volume::PhantomKind::Ct));
}

// The phantom's voxels on thick slices (0.5 mm pixels, 3 mm slices): drawn through the
// shape-based field, a copy per iso-value.
inline std::shared_ptr<const volume::Volume> thickPhantom() {
    const volume::Volume thin = volume::makePhantom({72, 64, 40}, volume::PhantomKind::Ct);
    volume::Volume thick(thin.dims(), thin.voxelType(),
                         volume::VolumeGeometry::regular({0.0, 0.0, 0.0}, {0.5, 0.5, 3.0}));
    std::memcpy(thick.data(), thin.data(), thin.byteSize());
    thick.setValueMapping(thin.valueMapping());
    return std::make_shared<const volume::Volume>(std::move(thick));
}

inline Camera cameraAt(const volume::Volume& volume, double az, double el) {
    CameraSetup setup;
    setup.bounds = volumeBounds(volume);
    setup.azimuthDeg = az;
    setup.elevationDeg = el;
    return Camera(setup, 160, 120);
}

inline ReviewFrameRequest requestFor(const volume::Volume& volume, SilhouetteMethod method,
                                     Backend backend, double az) {
    ReviewFrameRequest request;
    request.iso = kIso;
    request.method = method;
    request.backend = backend;
    request.sampling.oversampling = Oversampling::Off;
    request.camera = cameraAt(volume, az, 20.0);
    request.wantSilhouette = true;
    request.wantIsoImage = true;
    request.isoCamera = request.camera;
    request.isoOptions.panel = GlPanel::Iso;
    return request;
}

// Pixels that differ from the top-left corner (the background) in any channel.
inline std::size_t drawnPixels(const core::ImageRgba8& image) {
    const core::Rgba8 background = image.pixels().front();
    std::size_t drawn = 0;
    for (const core::Rgba8& p : image.pixels())
        drawn += p.r != background.r || p.g != background.g || p.b != background.b;
    return drawn;
}

// The share of pixels whose channels all lie within `tolerance` of the other picture's.
inline double agreement(const core::ImageRgba8& a, const core::ImageRgba8& b, int tolerance) {
    if (a.width() != b.width() || a.height() != b.height())
        return 0.0;
    std::size_t same = 0;
    for (std::size_t i = 0; i < a.pixels().size(); ++i) {
        const core::Rgba8 p = a.pixels()[i], q = b.pixels()[i];
        same += std::abs(p.r - q.r) <= tolerance && std::abs(p.g - q.g) <= tolerance &&
                std::abs(p.b - q.b) <= tolerance;
    }
    return double(same) / double(a.pixels().size());
}

// A kept frame renderer moved to a new iso-value (`rebound`) against one made for it
// (`reference`): both drew, lines to compare at all, the same line mask and the same iso image.
inline void expectSameDrawing(const ReviewFrame& rebound, const ReviewFrame& reference,
                              double iso) {
    ASSERT_TRUE(rebound.silhouette && reference.silhouette && rebound.isoImage &&
                reference.isoImage);
    EXPECT_GT(reference.silhouette->lines.count(), 100u) << iso << ": lines drawn";
    EXPECT_TRUE(rebound.silhouette->lines == reference.silhouette->lines) << iso;
    EXPECT_EQ(agreement(*rebound.isoImage, *reference.isoImage, 0), 1.0) << iso;
}

} // namespace lw::render::test
