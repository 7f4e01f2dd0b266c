#include "lw/volume/slice_plane.h"

#include "lw/core/error.h"
#include "lw/core/parallel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace lw::volume {
namespace {

// Images stay at most this many pixels a side: a finer pixel than the screen can show costs
// sampling time and memory for nothing.
constexpr double kMaxImageSide = 2048.0;
// Index coordinates this close outside [0, dims - 1] still count as inside (rounding of the
// patient -> index map), clamped onto the border.
constexpr double kIndexTolerance = 1e-6;

std::array<glm::dvec3, 8> voxelCentreCorners(const Volume& volume) {
    const glm::dvec3 last = glm::dvec3(volume.dims() - 1);
    std::array<glm::dvec3, 8> corners;
    for (int c = 0; c < 8; ++c)
        corners[std::size_t(c)] = volume.geometry().indexToPatient(
            {(c & 1) ? last.x : 0.0, (c & 2) ? last.y : 0.0, (c & 4) ? last.z : 0.0});
    return corners;
}

// Spacing along `normal` of the grid axis most parallel to it (its spacing times |cos|).
double stepAlongNormal(const VolumeGeometry& geometry, glm::dvec3 normal) {
    const std::array<std::pair<glm::dvec3, double>, 3> axes = {
        std::pair{geometry.axisI(), geometry.spacingI()},
        std::pair{geometry.axisJ(), geometry.spacingJ()},
        std::pair{geometry.stackAxis(), geometry.sliceStep()}};
    double bestCos = -1.0, step = 1.0;
    for (const auto& [axis, spacing] : axes) {
        const double c = std::abs(glm::dot(axis, normal));
        if (c > bestCos) {
            bestCos = c;
            step = spacing * c;
        }
    }
    return step > 0.0 ? step : 1.0;
}

// Index coordinates inside [0, dims - 1] within the tolerance, clamped onto it; false outside.
bool clampIndex(glm::dvec3& ijk, glm::ivec3 dims) {
    for (int a = 0; a < 3; ++a) {
        const double last = double(dims[a] - 1);
        if (!(ijk[a] >= -kIndexTolerance && ijk[a] <= last + kIndexTolerance))
            return false;
        ijk[a] = std::clamp(ijk[a], 0.0, last);
    }
    return true;
}

// Trilinear interpolation of stored values at an index inside [0, dims - 1] (an axis of one
// sample has nothing to interpolate).
template <typename T> double trilinear(const T* voxels, glm::ivec3 dims, glm::dvec3 ijk) {
    const int i0 = std::min(int(ijk.x), std::max(dims.x - 2, 0));
    const int j0 = std::min(int(ijk.y), std::max(dims.y - 2, 0));
    const int k0 = std::min(int(ijk.z), std::max(dims.z - 2, 0));
    const double fi = ijk.x - i0, fj = ijk.y - j0, fk = ijk.z - k0;
    const std::ptrdiff_t di = dims.x > 1 ? 1 : 0;
    const std::ptrdiff_t dj = dims.y > 1 ? dims.x : 0;
    const std::ptrdiff_t dk = dims.z > 1 ? std::ptrdiff_t(dims.x) * dims.y : 0;
    const T* p = voxels + i0 + std::ptrdiff_t(dims.x) * (j0 + std::ptrdiff_t(dims.y) * k0);
    const double c00 = p[0] + fi * (double(p[di]) - p[0]);
    const double c10 = p[dj] + fi * (double(p[dj + di]) - p[dj]);
    const double c01 = p[dk] + fi * (double(p[dk + di]) - p[dk]);
    const double c11 = p[dk + dj] + fi * (double(p[dk + dj + di]) - p[dk + dj]);
    const double c0 = c00 + fj * (c10 - c00);
    const double c1 = c01 + fj * (c11 - c01);
    return c0 + fk * (c1 - c0);
}

double trilinearReal(const Volume& volume, glm::dvec3 ijk) {
    const double stored = dispatchVoxelType(volume.voxelType(), [&](auto tag) {
        using T = decltype(tag);
        return trilinear(volume.dataAs<T>(), volume.dims(), ijk);
    });
    return volume.valueMapping().toReal(stored);
}

// Index coordinates along one image row: i, j and the stack offset are affine in the pixel
// (the slice planes are parallel), only the slice index needs the inverse offset lookup of an
// uneven stack.
struct RowWalk {
    glm::dvec3 start; // (i, j, offset along the stack axis) at pixel u = 0
    glm::dvec3 delta; // change per pixel
};

// (i, j, stack offset) of a patient point: patientToIndex without the offset's inversion.
glm::dvec3 indexAndOffset(const VolumeGeometry& geometry, glm::dvec3 patient) {
    const glm::dvec3 ijk = geometry.patientToIndex(patient);
    const glm::dvec3 normal = geometry.sliceNormal();
    const double offset =
        glm::dot(patient - geometry.origin(), normal) / glm::dot(geometry.stackAxis(), normal);
    return {ijk.x, ijk.y, offset};
}

RowWalk rowWalk(const VolumeGeometry& volumeGeometry, const SliceGeometry& slice, int row,
                double position) {
    const glm::dvec3 a = indexAndOffset(volumeGeometry, slice.patientPoint({0.0, row}, position));
    const glm::dvec3 b = indexAndOffset(volumeGeometry, slice.patientPoint({1.0, row}, position));
    return {a, b - a};
}

template <typename T>
void sampleRow(const Volume& volume, const RowWalk& walk, const ValueMapping& mapping, float* out,
               int width) {
    const T* voxels = volume.dataAs<T>();
    const glm::ivec3 dims = volume.dims();
    const VolumeGeometry& geometry = volume.geometry();
    const bool uniform = geometry.sliceOffsets().size() < 2;
    const double kPerOffset = uniform ? 1.0 / geometry.sliceStep() : 0.0;
    const float outside = std::numeric_limits<float>::quiet_NaN();
    for (int u = 0; u < width; ++u) {
        const glm::dvec3 iOff = walk.start + double(u) * walk.delta;
        glm::dvec3 ijk{iOff.x, iOff.y,
                       uniform ? iOff.z * kPerOffset : geometry.sliceIndexAtOffset(iOff.z)};
        out[u] =
            clampIndex(ijk, dims) ? float(mapping.toReal(trilinear(voxels, dims, ijk))) : outside;
    }
}

} // namespace

std::string_view sliceOrientationName(SliceOrientation orientation) {
    switch (orientation) {
    case SliceOrientation::Axial:
        return "axial";
    case SliceOrientation::Coronal:
        return "coronal";
    case SliceOrientation::Sagittal:
        return "sagittal";
    }
    return "?";
}

std::optional<SliceOrientation> parseSliceOrientation(std::string_view name) {
    for (SliceOrientation o :
         {SliceOrientation::Axial, SliceOrientation::Coronal, SliceOrientation::Sagittal})
        if (sliceOrientationName(o) == name)
            return o;
    return std::nullopt;
}

SliceAxes sliceAxes(SliceOrientation orientation) {
    switch (orientation) {
    case SliceOrientation::Axial:
        return {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    case SliceOrientation::Coronal:
        return {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}};
    case SliceOrientation::Sagittal:
        return {{0, 1, 0}, {0, 0, -1}, {1, 0, 0}};
    }
    throw core::Error("slice plane", "unknown orientation");
}

SliceEdgeLabels sliceEdgeLabels(SliceOrientation orientation) {
    switch (orientation) {
    case SliceOrientation::Axial:
        return {'R', 'L', 'A', 'P'};
    case SliceOrientation::Coronal:
        return {'R', 'L', 'S', 'I'};
    case SliceOrientation::Sagittal:
        return {'A', 'P', 'S', 'I'};
    }
    throw core::Error("slice plane", "unknown orientation");
}

glm::dvec3 SliceGeometry::patientPoint(glm::dvec2 pixel, double position) const {
    const glm::dvec2 mm = originMm + pixel * pixelMm;
    return mm.x * axes.right + mm.y * axes.down + position * axes.normal;
}

glm::dvec2 SliceGeometry::pixelOf(glm::dvec3 patient) const {
    const glm::dvec2 mm{glm::dot(patient, axes.right), glm::dot(patient, axes.down)};
    return (mm - originMm) / pixelMm;
}

double SliceGeometry::positionOf(glm::dvec3 patient) const {
    return glm::dot(patient, axes.normal);
}

SliceGeometry sliceGeometry(const Volume& volume, SliceOrientation orientation) {
    if (volume.isEmpty())
        throw core::Error("slice plane", "the volume is empty");
    const VolumeGeometry& g = volume.geometry();
    SliceGeometry slice;
    slice.orientation = orientation;
    slice.axes = sliceAxes(orientation);
    glm::dvec2 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
    slice.firstPosition = std::numeric_limits<double>::max();
    slice.lastPosition = std::numeric_limits<double>::lowest();
    for (const glm::dvec3& corner : voxelCentreCorners(volume)) {
        const glm::dvec2 mm{glm::dot(corner, slice.axes.right), glm::dot(corner, slice.axes.down)};
        lo = glm::min(lo, mm);
        hi = glm::max(hi, mm);
        slice.firstPosition = std::min(slice.firstPosition, slice.positionOf(corner));
        slice.lastPosition = std::max(slice.lastPosition, slice.positionOf(corner));
    }
    const double finest = std::min({g.spacingI(), g.spacingJ(), g.sliceStepAlongNormal()});
    const glm::dvec2 extent = hi - lo;
    const double coarsestNeeded = std::max(extent.x, extent.y) / (kMaxImageSide - 1.0);
    slice.pixelMm = std::max(finest > 0.0 ? finest : 1.0, coarsestNeeded);
    slice.originMm = lo;
    // Pixels enough to reach the far corner (within rounding of a whole number of pixels).
    slice.size = glm::ivec2(glm::ceil(extent / slice.pixelMm - 1e-9)) + 1;
    slice.step = stepAlongNormal(g, slice.axes.normal);
    return slice;
}

SliceImage sampleSlice(const Volume& volume, const SliceGeometry& geometry, double position,
                       unsigned threads) {
    SliceImage image;
    image.geometry = geometry;
    image.position = position;
    const int width = geometry.size.x, height = geometry.size.y;
    if (width <= 0 || height <= 0 || volume.isEmpty())
        return image;
    image.values.resize(std::size_t(width) * std::size_t(height));
    dispatchVoxelType(volume.voxelType(), [&](auto tag) {
        using T = decltype(tag);
        core::parallelForRanges(
            std::size_t(height), 8,
            [&](std::size_t begin, std::size_t end) {
                for (std::size_t v = begin; v < end; ++v)
                    sampleRow<T>(volume, rowWalk(volume.geometry(), geometry, int(v), position),
                                 volume.valueMapping(),
                                 image.values.data() + v * std::size_t(width), width);
            },
            threads);
    });
    return image;
}

std::optional<double> sampleAt(const Volume& volume, glm::dvec3 patient) {
    if (volume.isEmpty())
        return std::nullopt;
    glm::dvec3 ijk = volume.geometry().patientToIndex(patient);
    if (!clampIndex(ijk, volume.dims()))
        return std::nullopt;
    return trilinearReal(volume, ijk);
}

void windowToGrey(const SliceImage& slice, double width, double level, std::uint8_t* grey,
                  std::size_t stride) {
    const glm::ivec2 size = slice.geometry.size;
    const float low = float(level - 0.5 * width);
    const float scale = float(255.0 / std::max(width, 1e-6));
    for (int y = 0; y < size.y; ++y) {
        std::uint8_t* row = grey + std::size_t(y) * stride;
        const float* values = slice.values.data() + std::size_t(y) * std::size_t(size.x);
        for (int x = 0; x < size.x; ++x) {
            const float value = (values[x] - low) * scale; // NaN stays NaN: black below
            row[x] = value > 0.0f ? std::uint8_t(std::min(value, 255.0f) + 0.5f) : 0;
        }
    }
}

} // namespace lw::volume
