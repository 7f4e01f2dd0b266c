#pragma once

// Orthogonal slices through a volume in patient space (multiplanar reformatting): axial,
// coronal and sagittal planes of the patient's LPS frame, whatever the scanner's grid. A tilted
// or unevenly spaced stack is sampled where each voxel lies (VolumeGeometry::patientToIndex),
// so a slice is never shown sheared.
//
// Patient axes are DICOM's LPS: +x towards the patient's left, +y posterior, +z superior. The
// images follow the radiological convention (as Horos, Weasis and 3D Slicer show them):
//
//   axial (from the feet)      coronal (from the front)    sagittal (from the patient's left)
//            A                           S                            S
//        +------+                    +------+                     +------+
//      R |  -> +x (right)          R |  -> +x                   A |  -> +y (right)
//        |  v  +y (down)             |  v  -z                     |  v  -z
//        +------+ L                  +------+ L                   +------+ P
//            P                           I                            I
//   position: z (mm), + superior   position: y, + posterior     position: x, + left
//
// Image pixel (u, v) has its centre at originMm + (u, v) * pixelMm in the plane's (right, down)
// coordinates; a patient point p is at (dot(p, right), dot(p, down)) there and at position
// dot(p, normal) along the plane's normal.

#include "lw/volume/volume.h"

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <string_view>
#include <vector>

namespace lw::volume {

enum class SliceOrientation { Axial, Coronal, Sagittal };

std::string_view
sliceOrientationName(SliceOrientation orientation); // "axial" | "coronal" | "sagittal"
std::optional<SliceOrientation> parseSliceOrientation(std::string_view name);

// The plane's frame in patient coordinates (unit vectors, right x down == normal or its
// opposite: see the diagram).
struct SliceAxes {
    glm::dvec3 right{1, 0, 0};
    glm::dvec3 down{0, 1, 0};
    glm::dvec3 normal{0, 0, 1};
};
SliceAxes sliceAxes(SliceOrientation orientation);

// The patient direction letter at each edge of the image ("R", "L", "A", "P", "S", "I").
struct SliceEdgeLabels {
    char left = 'R';
    char right = 'L';
    char top = 'A';
    char bottom = 'P';
};
SliceEdgeLabels sliceEdgeLabels(SliceOrientation orientation);

// Where one orientation's slices lie through a volume: an image rectangle that covers the
// volume's box at every position, the range of positions and the step between slices.
struct SliceGeometry {
    SliceOrientation orientation = SliceOrientation::Axial;
    SliceAxes axes;
    glm::dvec2 originMm{0.0};   // (right, down) coordinates of pixel (0, 0)'s centre
    double pixelMm = 1.0;       // square pixels: the volume's finest spacing
    glm::ivec2 size{0};         // pixels
    double firstPosition = 0.0; // along axes.normal, mm: the voxel centres' extent
    double lastPosition = 0.0;
    double step = 1.0; // mm along the normal from one of the volume's slices to the next

    double middlePosition() const { return 0.5 * (firstPosition + lastPosition); }
    // The patient point at image coordinates `pixel` (pixel centres at integers) and `position`.
    glm::dvec3 patientPoint(glm::dvec2 pixel, double position) const;
    // Image coordinates of a patient point (its projection onto the plane).
    glm::dvec2 pixelOf(glm::dvec3 patient) const;
    // Position of a patient point along the normal.
    double positionOf(glm::dvec3 patient) const;
};
SliceGeometry sliceGeometry(const Volume& volume, SliceOrientation orientation);

// One resampled slice: real values (HU for CT, after the value mapping), NaN outside the
// volume's voxel centres; row-major, size.x values a row.
struct SliceImage {
    SliceGeometry geometry;
    double position = 0.0;
    std::vector<float> values;

    float at(int x, int y) const {
        return values[std::size_t(y) * std::size_t(geometry.size.x) + std::size_t(x)];
    }
};

// `volume` sampled trilinearly on the plane at `position`: within a slice bilinearly, between
// slices linearly along the stack where the scanner placed them. `geometry` may come from
// another volume over the same patient space (a finer copy samples on its source's pixels).
SliceImage sampleSlice(const Volume& volume, const SliceGeometry& geometry, double position,
                       unsigned threads = 0);

// `slice` under a window: grey 0 at level - width/2 and below (and outside the volume, NaN), 255
// at level + width/2 and above, linear between; row y goes to grey + y * stride (the review's
// panels and the CLI's PNG window the same way).
void windowToGrey(const SliceImage& slice, double width, double level, std::uint8_t* grey,
                  std::size_t stride);

// The real value at a patient point (trilinear, as sampleSlice), or nothing outside the voxel
// centres' box.
std::optional<double> sampleAt(const Volume& volume, glm::dvec3 patient);

} // namespace lw::volume
