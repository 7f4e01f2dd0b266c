#pragma once

// The voxel grid as marching cubes sees it: per-axis derivative spans, the gradient behind the
// vertex normals, and (host side) their set-up from the volume geometry. Method 2 rebuilds the
// marching-cubes vertices cell by cell and must reproduce them bit for bit, so marching cubes,
// method 2 and the CUDA backend all take these from this one definition.

#include "lw/kernels/host_device.h"
#include "lw/kernels/marching_cubes.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <glm/glm.hpp>
#include <limits>
#include <utility>
#include <vector>

namespace lw::kernels {

// Voxel dims, cell dims (voxels - 1 per axis) and the voxel strides of +y and +z.
struct GridDims {
    int nx = 0, ny = 0, nz = 0;
    int cx = 0, cy = 0, cz = 0;
    std::size_t sy = 0, sz = 0;
};

inline GridDims makeGridDims(glm::ivec3 voxels) {
    GridDims d;
    d.nx = voxels.x;
    d.ny = voxels.y;
    d.nz = voxels.z;
    d.cx = d.nx - 1;
    d.cy = d.ny - 1;
    d.cz = d.nz - 1;
    d.sy = std::size_t(d.nx);
    d.sz = std::size_t(d.nx) * std::size_t(d.ny);
    return d;
}

// Which finite differences the gradient takes (VoxelGradientSampler::gradient).
//   Central:  d/dx at (x, y, z) = (v[x+1] - v[x-1]) / span, one-sided at the faces -- 6 voxels.
//   Smoothed: the same difference taken at the 3 x 3 grid points across the axis and averaged
//             with weights (s, 1 - 2s, s) along each cross axis -- for square pixels and
//             isotropic voxels s = 1/4 everywhere, the 3D Sobel-Feldman operator (26 voxels):
//
//                 cross axis b       -1    0   +1
//             cross axis a   -1       1    2    1
//                             0       2    4    2     (/ 16; each weight multiplies the
//                            +1       1    2    1      difference along the axis there)
//
//             The weights are a Gaussian of the real distance, 1/2 at one in-plane pixel
//             (GridSpans::crossSide): across slices thicker than the pixel s falls off fast
//             (0.0008 for 4 mm slices of 1.25 mm pixels, 0 beyond), so a thick-slice series is
//             smoothed in-plane only and an edge crossing a slab keeps its slab. Voxel-wide noise
//             bumps no longer tilt the normals; a neighbour beyond a face is the face's own grid
//             point (replicated), so the weights stay positive and sum to 1.
enum class GradientStencil : unsigned char { Central, Smoothed };

// The real distances (mm) a derivative divides by, per axis. In-plane the central difference
// spans two spacings and the one-sided one at a face one spacing; across slices the span is the
// actual distance between the neighbouring slices (uneven gaps), one gap at the first and last
// slice. Plain values and pointers, so it can be copied to a device.
struct GridSpans {
    GridDims dims;
    float spanI = 2.0f, spanJ = 2.0f;
    // The interior fast path multiplies by these instead of dividing; invSpanJ is rounded from
    // double, invSpanI from the float span (as first written: keep, the normals depend on it).
    float invSpanI = 0.5f, invSpanJ = 0.5f;
    float edgeSpanI = 1.0f, edgeSpanJ = 1.0f;
    const float* spanK = nullptr;    // per slice
    const float* invSpanK = nullptr; // per slice, 0 where spanK is 0
    GradientStencil stencil = GradientStencil::Central;
    // GradientStencil::Smoothed: the weight s of each of the two neighbours across axis 0, 1, 2
    // (the centre's is 1 - 2s): 0.5^((spacing / pixel)^2) / (1 + 2 * that), pixel the smaller
    // in-plane spacing, the slices' median gap for axis 2; below 1e-3 it is 0 (not evaluated).
    float crossSide[3] = {0.25f, 0.25f, 0.25f};
};

// Host side: GridSpans and McGridFrame of a volume, from its geometry (VolumeGeometry's values:
// kernels/common does not see lw::volume) and the offset of each slice along the stack axis.
// Owns the per-slice tables they point into, so it is neither copied nor moved.
class VoxelGridSetup {
public:
    VoxelGridSetup(glm::ivec3 dims, glm::dvec3 origin, glm::dvec3 axisI, glm::dvec3 axisJ,
                   glm::dvec3 stackAxis, double spacingI, double spacingJ,
                   std::vector<double> sliceOffsets,
                   GradientStencil stencil = GradientStencil::Central)
        : m_origin(origin), m_stepI(spacingI * axisI), m_stepJ(spacingJ * axisJ),
          m_stack(stackAxis), m_offset(std::move(sliceOffsets)) {
        const int nz = dims.z;
        m_offset.resize(std::size_t(nz > 1 ? nz : 1));
        m_spans.dims = makeGridDims(dims);
        // Real distance between the neighbours used for d/ds at slice k (uneven gaps).
        m_spanK.resize(m_offset.size());
        m_invSpanK.resize(m_offset.size());
        for (int k = 0; k < nz; ++k) {
            const std::size_t kk = std::size_t(k);
            m_spanK[kk] = float(m_offset[std::size_t(k + 1 < nz ? k + 1 : nz - 1)] -
                                m_offset[std::size_t(k > 0 ? k - 1 : 0)]);
            m_invSpanK[kk] = m_spanK[kk] > 0.0f ? 1.0f / m_spanK[kk] : 0.0f;
        }
        m_spans.spanI = float(2.0 * spacingI);
        m_spans.spanJ = float(2.0 * spacingJ);
        m_spans.invSpanI = 1.0f / m_spans.spanI;
        m_spans.invSpanJ = float(1.0 / (2.0 * spacingJ));
        m_spans.edgeSpanI = float(spacingI);
        m_spans.edgeSpanJ = float(spacingJ);
        m_spans.spanK = m_spanK.data();
        m_spans.invSpanK = m_invSpanK.data();
        m_spans.stencil = stencil;
        const double pixel = std::min(spacingI, spacingJ);
        m_spans.crossSide[0] = crossSideWeight(spacingI, pixel);
        m_spans.crossSide[1] = crossSideWeight(spacingJ, pixel);
        m_spans.crossSide[2] = crossSideWeight(medianGap(m_offset), pixel);

        for (int c = 0; c < 3; ++c) {
            m_frame.origin[c] = m_origin[c];
            m_frame.stepI[c] = m_stepI[c];
            m_frame.stepJ[c] = m_stepJ[c];
            m_frame.stack[c] = m_stack[c];
        }
        m_frame.sliceOffset = m_offset.data();
        m_frame.edgeLength[0] = float(glm::length(m_stepI));
        m_frame.edgeLength[1] = float(glm::length(m_stepJ));
        m_frame.thickSlabEdge = thickSlabEdgeLength(m_frame.edgeLength[0], m_frame.edgeLength[1]);
        // Derivatives are taken in the oblique frame (axisI, axisJ, stackAxis) with real
        // distances; the patient gradient is M^-T (du, dw, ds) with M the frame's columns --
        // the same as J(k)^-T applied to the index-space gradient.
        const glm::dmat3 frame(axisI, axisJ, stackAxis);
        const glm::dmat3 invT = glm::inverse(glm::transpose(frame));
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                m_frame.normalMatrix[r * 3 + c] = float(invT[c][r]);
        glm::dvec3 axisDir[3];
        axisDir[0] = glm::normalize(axisI);
        axisDir[1] = glm::normalize(axisJ);
        double slope = 1.0;
        if (nz > 1)
            slope = m_offset.back() - m_offset.front() >= 0.0 ? 1.0 : -1.0;
        axisDir[2] = glm::normalize(stackAxis) * slope;
        for (int a = 0; a < 3; ++a)
            m_frame.edgeDirection[a] = {float(axisDir[a].x), float(axisDir[a].y),
                                        float(axisDir[a].z)};
    }
    VoxelGridSetup(const VoxelGridSetup&) = delete;
    VoxelGridSetup& operator=(const VoxelGridSetup&) = delete;

    const GridSpans& spans() const { return m_spans; }
    const McGridFrame& frame() const { return m_frame; }
    // Per slice; at least one entry.
    const std::vector<double>& sliceOffsets() const { return m_offset; }
    glm::dvec3 origin() const { return m_origin; }
    glm::dvec3 stepI() const { return m_stepI; } // spacingI * axisI
    glm::dvec3 stepJ() const { return m_stepJ; } // spacingJ * axisJ
    glm::dvec3 stack() const { return m_stack; } // stackAxis

private:
    // GridSpans::crossSide for neighbours `distance` mm away.
    static float crossSideWeight(double distance, double pixel) {
        if (!(pixel > 0.0) || !(distance > 0.0))
            return 0.0f;
        const double ratio = distance / pixel;
        const double relative = std::pow(0.5, ratio * ratio);
        const double side = relative / (1.0 + 2.0 * relative);
        return side < 1e-3 ? 0.0f : float(side);
    }
    static double medianGap(const std::vector<double>& offsets) {
        std::vector<double> gaps;
        for (std::size_t k = 1; k < offsets.size(); ++k)
            gaps.push_back(std::abs(offsets[k] - offsets[k - 1]));
        if (gaps.empty())
            return 0.0;
        std::nth_element(gaps.begin(), gaps.begin() + std::ptrdiff_t(gaps.size() / 2), gaps.end());
        return gaps[gaps.size() / 2];
    }

    static float thickSlabEdgeLength(float edgeI, float edgeJ) {
        const float pixel = edgeI < edgeJ ? edgeI : edgeJ;
        return pixel > 0.0f ? kThickSlabOverPixel * pixel : std::numeric_limits<float>::infinity();
    }

    glm::dvec3 m_origin, m_stepI, m_stepJ, m_stack;
    std::vector<double> m_offset;
    std::vector<float> m_spanK, m_invSpanK;
    GridSpans m_spans;
    McGridFrame m_frame{};
};

// Gradient of the voxel field at grid points, in the oblique (axisI, axisJ, stackAxis) frame,
// per mm: central differences inside, one-sided at the faces.
template <typename T> struct VoxelGradientSampler {
    const T* voxels = nullptr;
    GridSpans spans;
    // For a box of the volume held on its own (the CUDA back-end's streamed bricks): spans.dims
    // keeps the whole volume's sizes (faces, one-sided differences) but its sy/sz are the box's
    // strides, and voxel (x, y, z) of the volume sits at x + sy y + sz z - indexOrigin in the box
    // (unsigned arithmetic wraps exactly). 0 for a whole volume.
    std::size_t indexOrigin = 0;

    LW_HOST_DEVICE float value(std::size_t index) const { return float(voxels[index]); }

    LW_HOST_DEVICE McVec3 gradient(int x, int y, int z) const {
        return spans.stencil == GradientStencil::Smoothed ? smoothedGradient(x, y, z)
                                                          : centralGradient(x, y, z);
    }

    LW_HOST_DEVICE McVec3 centralGradient(int x, int y, int z) const {
        const int cx = spans.dims.cx, cy = spans.dims.cy, cz = spans.dims.cz;
        const std::size_t sy = spans.dims.sy, sz = spans.dims.sz;
        const std::size_t i =
            std::size_t(x) + sy * std::size_t(y) + sz * std::size_t(z) - indexOrigin;
        if (x > 0 && x < cx && y > 0 && y < cy && z > 0 && z < cz) {
            // Interior: central differences everywhere, no boundary cases.
            return {(value(i + 1) - value(i - 1)) * spans.invSpanI,
                    (value(i + sy) - value(i - sy)) * spans.invSpanJ,
                    (value(i + sz) - value(i - sz)) * spans.invSpanK[std::size_t(z)]};
        }
        // At a face: per axis, central or one-sided (the expressions smoothedGradient takes too).
        return {axisDifference(0, x, y, z), axisDifference(1, x, y, z), axisDifference(2, x, y, z)};
    }

    // GradientStencil::Smoothed (diagram at the enum): each component is the difference along
    // its axis averaged over the 3 x 3 grid points across it, weighted by spans.crossSide.
    LW_HOST_DEVICE McVec3 smoothedGradient(int x, int y, int z) const {
        const GridDims& d = spans.dims;
        McVec3 g{0.0f, 0.0f, 0.0f};
        for (int b = -1; b <= 1; ++b) {
            for (int a = -1; a <= 1; ++a) {
                const float wx = crossWeight(1, a) * crossWeight(2, b);
                const float wy = crossWeight(0, a) * crossWeight(2, b);
                const float wz = crossWeight(0, a) * crossWeight(1, b);
                if (wx > 0.0f)
                    g.x += wx * axisDifference(0, x, clampTo(y + a, d.cy), clampTo(z + b, d.cz));
                if (wy > 0.0f)
                    g.y += wy * axisDifference(1, clampTo(x + a, d.cx), y, clampTo(z + b, d.cz));
                if (wz > 0.0f)
                    g.z += wz * axisDifference(2, clampTo(x + a, d.cx), clampTo(y + b, d.cy), z);
            }
        }
        return g;
    }

    // mcEdgeVertex of the edge leaving voxel (x, y, z) along `axis`, with its end values read
    // here; ga/gb are gradient() at the edge's lower and upper voxel (callers reuse them).
    LW_HOST_DEVICE McVertex edgeVertex(const McGridFrame& frame, int x, int y, int z, int axis,
                                       const McVec3& ga, const McVec3& gb, double iso,
                                       float isoF) const {
        const std::size_t i = std::size_t(x) + spans.dims.sy * std::size_t(y) +
                              spans.dims.sz * std::size_t(z) - indexOrigin;
        const std::size_t step = axis == 0 ? 1 : (axis == 1 ? spans.dims.sy : spans.dims.sz);
        return mcEdgeVertex(frame, x, y, z, axis, value(i), value(i + step), ga, gb, iso, isoF);
    }

private:
    LW_HOST_DEVICE float crossWeight(int axis, int offset) const {
        return offset == 0 ? 1.0f - 2.0f * spans.crossSide[axis] : spans.crossSide[axis];
    }

    LW_HOST_DEVICE static int clampTo(int v, int last) { return v < 0 ? 0 : (v > last ? last : v); }

    // The derivative along one axis at grid point (x, y, z): central inside, one-sided at a face
    // (one gap across the first and last slice), 0 along an axis of one voxel.
    LW_HOST_DEVICE float axisDifference(int axis, int x, int y, int z) const {
        const GridDims& d = spans.dims;
        const std::size_t i =
            std::size_t(x) + d.sy * std::size_t(y) + d.sz * std::size_t(z) - indexOrigin;
        if (axis == 2) {
            const float c = value(i);
            return mcDerivative(z > 0 ? value(i - d.sz) : c, z < d.cz ? value(i + d.sz) : c,
                                spans.spanK[std::size_t(z)]);
        }
        const int at = axis == 0 ? x : y, last = axis == 0 ? d.cx : d.cy;
        const std::size_t step = axis == 0 ? 1 : d.sy;
        if (last == 0)
            return 0.0f;
        const float span = axis == 0 ? spans.spanI : spans.spanJ;
        const float edgeSpan = axis == 0 ? spans.edgeSpanI : spans.edgeSpanJ;
        if (at > 0 && at < last)
            return mcDerivative(value(i - step), value(i + step), span);
        return at == 0 ? mcDerivative(value(i), value(i + step), edgeSpan)
                       : mcDerivative(value(i - step), value(i), edgeSpan);
    }
};

} // namespace lw::kernels
