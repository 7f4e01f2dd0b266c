#pragma once

// How finely the methods sample a volume's field: as loaded, or oversampled where its cells
// would come out large in the picture (volume/oversampling.h says why that matters and why the
// surface stays the same). The rule needs no view: the camera frames the whole volume, so a
// cell's share of the volume's diagonal is its share of the picture. Auto splits each axis
// until its cells are at most 1/kOversamplingCellsPerDiagonal of the diagonal (8 pixels of a
// 1024-pixel view), so coarse axes get finer and fine ones stay: a 5 mm series of a head gets
// 2.5 mm slabs, a 0.5 mm one nothing, and a refined axis never holds much more than 128
// samples, so the copy stays small.
//
// Thick slices (ThickSlices::Smooth, the default): where the slices are at least
// kThickSliceOverPixel times as far apart as the finer pixel spacing, the field drawn is the
// shape-based interpolation of the iso contours (volume/slice_distance.h says why grey values
// cannot avoid terraces there), with the slice axis split at least kThickSliceFactor times so
// the triangles follow the surface between the slices. That field is of one iso-value: a new
// iso-value needs a new copy (SamplingPlan::dependsOnIso). Everything drawn reads the copy --
// every method, S and L, CPU and CUDA, the shaded panel -- so they all draw the same surface.
// Grids that are not thick (analytic shapes, isotropic CT) are untouched.

#include "lw/render/renderer_factory.h"
#include "lw/volume/oversampling.h"
#include "lw/volume/volume.h"

#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string_view>

namespace lw::render {

enum class Oversampling { Off, Auto };
enum class ThickSlices { Linear, Smooth };

inline constexpr double kOversamplingCellsPerDiagonal = 128.0;
inline constexpr int kMaxOversamplingFactor = 8;

inline constexpr double kThickSliceOverPixel = 3.0;
inline constexpr int kThickSliceFactor = 3;
// The shape-based field's distance limit in slice steps (volume/slice_distance.h).
inline constexpr double kThickSliceDistanceLimitSteps = 1.0;
// The widest wall the shape-based field slides between thick slices (volume/slice_bridging.h):
// a skull's, with room for the partial volume of thick slices. Measured against 6, 14 and 20 mm
// on the thick-against-thin series (docs/BENCHMARKS.md).
inline constexpr double kThickSliceThinWallMm = 10.0;

std::string_view oversamplingName(Oversampling oversampling); // "off" | "auto"
std::optional<Oversampling> parseOversampling(std::string_view name);
std::string_view thickSlicesName(ThickSlices thickSlices); // "linear" | "smooth"
std::optional<ThickSlices> parseThickSlices(std::string_view name);

// How the methods sample a volume: the two choices above (Settings and the CLI's --oversample
// and --thick-slices), and the widest wall slid between thick slices (the CLI's --thin-walls; 0:
// none, the shape-based field point by point).
struct VolumeSampling {
    Oversampling oversampling = Oversampling::Auto;
    ThickSlices thickSlices = ThickSlices::Smooth;
    double thinWallMm = kThickSliceThinWallMm;
    bool operator==(const VolumeSampling&) const = default;
};
// The grid as loaded: what `bench` and `accuracy` measure by default.
inline constexpr VolumeSampling kSamplingAsLoaded{Oversampling::Off, ThickSlices::Linear};

// What a sampling makes of one volume: the factors along (i, j, k), whether the field is the
// slices' signed distance to the iso contour (shape-based) and how the slice axis is
// interpolated. All factors 1 means the volume as loaded.
struct SamplingPlan {
    glm::ivec3 factors{1};
    bool shapeBased = false;
    volume::SliceInterpolation alongSlices = volume::SliceInterpolation::Linear;
    double thinWallMm = 0.0; // walls up to this wide slide between the slices (shape-based only)
    bool asLoaded() const { return factors == glm::ivec3(1) && !shapeBased; }
    bool dependsOnIso() const { return shapeBased; }
};

// True where the mean slice step (along the slice normal) is at least kThickSliceOverPixel times
// the finer pixel spacing, on a stack of at least three slices.
bool hasThickSlices(glm::ivec3 dims, const volume::VolumeGeometry& geometry);
SamplingPlan samplingPlan(glm::ivec3 dims, const volume::VolumeGeometry& geometry,
                          VolumeSampling sampling);

// The factors along (i, j, k) that `oversampling` gives a volume of `dims` on `geometry`:
// (1, 1, 1) for Off, for a volume of one voxel along every axis, or when no cell is too large.
glm::ivec3 oversamplingFactors(glm::ivec3 dims, const volume::VolumeGeometry& geometry,
                               Oversampling oversampling);

// `volume` resampled by samplingPlan (volume::signedSliceDistance at `iso` where shape-based,
// then volume::oversampled; logged on lw.render), or nothing where the plan keeps it as
// loaded: the volume itself is the one to draw. `iso` (real units) matters only where the plan
// dependsOnIso.
std::optional<volume::Volume> oversampledToRender(const volume::Volume& volume,
                                                  VolumeSampling sampling, double iso,
                                                  unsigned threads = 0);

// The volume the methods draw: `volume` itself where the plan keeps it as loaded, else its
// resampled copy.
std::shared_ptr<const volume::Volume> volumeToRender(std::shared_ptr<const volume::Volume> volume,
                                                     VolumeSampling sampling, double iso,
                                                     unsigned threads = 0);

// The stages of a copy made on the device (CUDA events, ms; refinement includes the thin walls and
// the faces' maxima).
struct DeviceCopyTimes {
    double distanceMs = 0.0, refinementMs = 0.0, downloadMs = 0.0;
};

// The volume to draw of one source, made again only when the sampling or (for the shape-based
// field) the iso-value changes. On the CUDA back-end the shape-based field is made on the device
// (kernels/cuda/thick_slice_field_cuda.h: the same int16 copy, bit for bit): the slices go up
// once, and a new iso-value costs a few kernels and the copy's download instead of the host's
// distance transform and refinement. Where the device fails (out of memory, no device after all),
// the host makes it from then on, and takeNote() says why once. The device path's host copies
// are written again once nobody else holds them (fresh pages for each iso-value cost their page
// faults); a copy is never written while anyone holds it.
class DrawnVolumeMaker {
public:
    DrawnVolumeMaker(std::shared_ptr<const volume::Volume> source, Backend backend);
    ~DrawnVolumeMaker();
    DrawnVolumeMaker(const DrawnVolumeMaker&) = delete;
    DrawnVolumeMaker& operator=(const DrawnVolumeMaker&) = delete;

    // volumeToRender's volume for `sampling` at `iso`.
    std::shared_ptr<const volume::Volume> make(VolumeSampling sampling, double iso,
                                               unsigned threads = 0);
    bool lastMadeOnDevice() const;
    // The last copy's voxels in device memory where it was made there (else null), valid until
    // the next make(): what the renderers of the copy take device to device
    // (SilhouetteRenderer::setVolumeWithDeviceCopy).
    DeviceVoxelCopy deviceCopy() const;
    // The last copy's stages where it was made on the device (else zeros).
    DeviceCopyTimes lastDeviceTimes() const;
    // Why the device stopped making the field ("" while it has not): once, then "".
    std::string takeNote();

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace lw::render
