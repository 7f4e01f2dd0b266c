#pragma once

// The thick-slice field on the device: per slice the signed distance to its iso contour, then
// refined along the slices by the monotone cubic (and in-plane linearly), thin walls slid between
// the slices -- the int16 volume that lw::volume's signedSliceDistance, oversampled(...,
// MonotoneCubic) and bridgeThinWalls make on the host, bit for bit (kernels/slice_field_rules.h
// and kernels/thin_shell_bridge.h hold the shared arithmetic).
//
// The field depends on the iso-value, so on the host a new iso-value costs a new field (the
// distance transform of every slice and the refinement of the whole copy). Here the slices are
// uploaded once per volume and each iso-value costs up to six kernels and one download:
//   above      per source voxel: the real value less the iso-value (float)
//   nearest    per pixel: the nearest crossing along its row and along its column (a window as
//              wide as the limit reaches, plus one pixel: crossings further away are beyond the
//              limit on both sides)
//   distance   per pixel: the minimum over the rows and columns within reach, stored as int16
//   refine     per refined voxel: the slices blended along k, then j, then i
//   bridge     per refined pixel of each gap: thin walls slid between the two slices, where
//              thinWallMm > 0 (volume/slice_bridging.h's pass on the host)
//   faces      per voxel of the refined field's six faces: each face's largest value
// Public header: no CUDA types.

#include "lw/kernels/cuda/cuda_status.h"
#include "lw/kernels/volume_view.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>

namespace lw::kernels::cuda {

struct ThickSliceFieldSetup {
    double slope = 1.0, intercept = 0.0;   // real = stored * slope + intercept
    double spacingI = 1.0, spacingJ = 1.0; // mm
    double limitMm = 1.0;                  // distances are limited to +-limitMm
    double stepsPerMm = 128.0;             // the int16's unit: 1/stepsPerMm mm
    glm::ivec3 factors{1};                 // refinement along (i, j, k); (n - 1) * f + 1 samples
    bool monotoneAlongSlices = true;       // else linear along k (as oversampled's Linear)
    double thinWallMm = 0.0;               // walls this wide slide between slices (0: none)
};

// Stage times of the last field and its download (CUDA events, ms; refineMs includes the bridge
// and the faces' maxima).
struct ThickSliceFieldTimes {
    double distanceMs = 0.0, refineMs = 0.0, downloadMs = 0.0;
    double totalMs() const { return distanceMs + refineMs + downloadMs; }
};

class ThickSliceFieldCuda {
public:
    ThickSliceFieldCuda();
    ~ThickSliceFieldCuda();
    ThickSliceFieldCuda(const ThickSliceFieldCuda&) = delete;
    ThickSliceFieldCuda& operator=(const ThickSliceFieldCuda&) = delete;

    // Uploads the slices (host memory; not referenced afterwards).
    CudaStatus setVolume(const VolumeView& hostVolume);
    // The field at `iso` (real units), downloaded into page-locked host memory: field() then holds
    // it, int16, x fastest, of the refined dims ((n - 1) * factor + 1 per axis of n > 1), until
    // the next make() or release(). Synchronous. (Page-locked, because a download into fresh
    // pageable memory runs at the speed of its page faults: 43 ms for the 43 MB of a 512^2 x 82
    // copy on an H200's host, against about 3 ms here; the caller copies it on with its threads.)
    // `lockedTarget`, where given: page-locked memory of the field's size (PageLockedHostRange)
    // the field is downloaded into instead, saving the caller that copy; field() is not written.
    CudaStatus make(double iso, const ThickSliceFieldSetup& setup,
                    std::int16_t* lockedTarget = nullptr);
    const std::int16_t* field() const;
    // The last field's largest value on each face (x low, x high, y low, y high, z low, z high:
    // lw::kernels::cpu::borderFaceMaxima's order and values), found on the device with it: a
    // renderer's border cap then need not read the faces of the host's copy, a voxel a row.
    const std::array<double, 6>& faceMaxima() const;
    // The same field in device memory, valid until the next make() or release(): what a renderer
    // of the copy takes device to device instead of uploading the host's (MarchingCubesCuda::
    // setDeviceVolume).
    const std::int16_t* deviceField() const;
    const ThickSliceFieldTimes& times() const;
    std::size_t deviceBytes() const;
    void release();

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace lw::kernels::cuda
