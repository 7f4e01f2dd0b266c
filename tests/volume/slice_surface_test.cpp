// The iso contour on a slice equals the cut of the 3D marching-cubes surface through that plane
// within half the smallest voxel spacing, both ways (issue 29's geometry goal), on an analytic
// sphere: sampled on a regular grid, and on a tilted, unevenly spaced one.
#include "filled_volume.h"
#include "lw/evaluation/analytic_shapes.h"
#include "lw/render/iso_surface.h"
#include "lw/volume/slice_contour.h"
#include "lw/volume/slice_plane.h"
#include "slice_cut.h"

#include <algorithm>
#include <cstdio>
#include <gtest/gtest.h>
#include <string>

namespace lw::volume {
namespace {

constexpr double kPi = 3.14159265358979323846;

double smallestSpacing(const VolumeGeometry& g) {
    double smallest = std::min(g.spacingI(), g.spacingJ());
    for (int k = 0; k + 1 < int(std::max<std::size_t>(g.sliceOffsets().size(), 2)); ++k)
        smallest = std::min(smallest, std::abs(g.sliceGap(k)) *
                                          std::abs(glm::dot(g.stackAxis(), g.sliceNormal())));
    return smallest;
}

// Contour against cut at several positions of each orientation; `margin` voxels at the
// volume's border are left out (the surface is open there, and the contour stops at NaN).
void expectContourEqualsCut(const Volume& volume, double iso, double margin) {
    const render::Mesh mesh = render::extractIsoSurface(volume, iso);
    ASSERT_FALSE(mesh.isEmpty());
    const double tolerance = 0.5 * smallestSpacing(volume.geometry());
    double worst = 0.0;
    for (SliceOrientation o :
         {SliceOrientation::Axial, SliceOrientation::Coronal, SliceOrientation::Sagittal}) {
        const SliceGeometry plane = sliceGeometry(volume, o);
        for (double position :
             test::positionsThroughMesh(mesh, plane, {0.15, 0.3, 0.5, 0.7, 0.85})) {
            SCOPED_TRACE(std::string(sliceOrientationName(o)) + " at " + std::to_string(position));
            const SliceImage image = sampleSlice(volume, plane, position);
            const std::vector<ContourSegment> contour = isoContour(image, iso);
            const std::vector<ContourSegment> cut = test::meshCut(mesh, plane, position);
            ASSERT_FALSE(contour.empty());
            ASSERT_FALSE(cut.empty());
            const auto awayFromBorder = [&](glm::dvec2 pixel) {
                const glm::dvec3 ijk =
                    volume.geometry().patientToIndex(plane.patientPoint(pixel, position));
                for (int a = 0; a < 3; ++a)
                    if (volume.dims()[a] > 1 &&
                        (ijk[a] < margin || ijk[a] > volume.dims()[a] - 1 - margin))
                        return false;
                return true;
            };
            const double reachPx = 4.0 * tolerance / plane.pixelMm;
            const test::SegmentGrid contourGrid(contour, 2.0), cutGrid(cut, 2.0);
            std::size_t compared = 0;
            const double cutToContour =
                test::largestDistance(cut, contourGrid, 0.25, reachPx, awayFromBorder, &compared) *
                plane.pixelMm;
            const double contourToCut =
                test::largestDistance(contour, cutGrid, 0.25, reachPx, awayFromBorder, &compared) *
                plane.pixelMm;
            EXPECT_GT(compared, 100u);
            EXPECT_LE(cutToContour, tolerance);
            EXPECT_LE(contourToCut, tolerance);
            worst = std::max({worst, cutToContour, contourToCut});
        }
    }
    std::printf("largest distance between the contour and the cut %.4f mm (tolerance %.3f mm)\n",
                worst, tolerance);
}

TEST(SliceContourAgainstMarchingCubes, AnalyticSphereOnARegularGrid) {
    const evaluation::SphereShape sphere({3.0, -2.0, 1.5}, 40.0);
    const Volume volume = evaluation::sampleShape(sphere, 72);
    expectContourEqualsCut(volume, evaluation::kShapeIso, 1.0);
}

TEST(SliceContourAgainstMarchingCubes, AnalyticSphereOnATiltedUnevenGrid) {
    // 18.5 degrees of tilt, gaps from 0.9 to 2.1 mm along the table, 0.8 x 0.9 mm pixels.
    const double t = 18.5 * kPi / 180.0;
    std::vector<glm::dvec3> positions{{-40.0, -35.0, -40.0}};
    for (int k = 1; k < 70; ++k)
        positions.push_back(positions.back() + glm::dvec3(0.0, 0.0, 1.5 + 0.6 * std::sin(1.7 * k)));
    const VolumeGeometry g = VolumeGeometry::fromSlicePositions(
        {1, 0, 0}, {0, std::cos(t), -std::sin(t)}, 0.8, 0.9, positions);
    ASSERT_FALSE(g.hasUniformSlices());
    const glm::dvec3 centre(1.0, 2.0, 3.0);
    const Volume volume = test::makeFilledVolume<float>(
        {100, 100, 70},
        [&](int x, int y, int z) {
            return 30.0 - glm::length(g.indexToPatient({x, y, z}) - centre);
        },
        g);
    expectContourEqualsCut(volume, 0.0, 1.0);
}

} // namespace
} // namespace lw::volume
