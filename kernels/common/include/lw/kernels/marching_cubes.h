#pragma once

// Host+device building blocks of marching cubes with gradient normals. They work on plain
// values so the CPU slab engine and a CUDA kernel evaluate exactly the same expressions.

#include "lw/kernels/host_device.h"
#include "lw/kernels/marching_cubes_tables.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>

namespace lw::kernels {

struct McVec3 {
    float x, y, z;
};

// Inside means value >= iso. `iso` is the smallest float that is >= the requested iso (see
// insideThreshold), so comparing floats here agrees with comparing the exact values.
LW_HOST_DEVICE inline bool mcInside(float value, float iso) {
    return value >= iso;
}

// The float threshold t with (v >= t) == (double(v) >= iso) for every float v.
inline float insideThreshold(double iso) {
    float t = float(iso);
    if (double(t) < iso)
        t = std::nextafter(t, INFINITY);
    return t;
}

// The inside test `value >= iso` done in the voxel type T: exact, and it lets row scans
// vectorise. For integer voxels v >= iso  <=>  v >= ceil(iso) (clamped to T's range: callers
// only classify when some brick has min < iso <= max); for float voxels insideThreshold(iso).
template <typename T> T voxelInsideThreshold(double iso) {
    if constexpr (std::is_integral_v<T>) {
        const double c = std::ceil(iso);
        return T(std::clamp(c, double(std::numeric_limits<T>::lowest()),
                            double(std::numeric_limits<T>::max())));
    } else {
        return T(insideThreshold(iso));
    }
}

// Case index from the eight corner values in diagram order.
LW_HOST_DEVICE inline int mcCaseIndex(const float v[8], float iso) {
    int c = 0;
    for (int i = 0; i < 8; ++i)
        c |= int(mcInside(v[i], iso)) << i;
    return c;
}

// Where along an edge from value a (t = 0) to value b (t = 1) the iso-value lies. Always
// evaluated from the edge's lower voxel to its upper one, whichever cell asks, so a shared
// vertex comes out bit-identical in every cell and every brick.
LW_HOST_DEVICE inline float mcEdgeParameter(double a, double b, double iso) {
    const double d = b - a;
    if (d == 0.0)
        return 0.5f;
    const double t = (iso - a) / d;
    return float(t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t));
}

// One-dimensional derivative at a grid point from its neighbours: central difference inside,
// one-sided at the ends. `lo`/`hi` are the neighbouring values (the point's own value where the
// neighbour is missing) and `span` the real distance between them.
LW_HOST_DEVICE inline float mcDerivative(float lo, float hi, float span) {
    return span > 0.0f ? (hi - lo) / span : 0.0f;
}

LW_HOST_DEVICE inline McVec3 mcLerp(McVec3 a, McVec3 b, float t) {
    return {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z)};
}

// Row-major 3x3 matrix times vector.
LW_HOST_DEVICE inline McVec3 mcTransform(const float m[9], McVec3 v) {
    return {m[0] * v.x + m[1] * v.y + m[2] * v.z, m[3] * v.x + m[4] * v.y + m[5] * v.z,
            m[6] * v.x + m[7] * v.y + m[8] * v.z};
}

// Outward unit normal from the (interpolated) patient-space gradient: the gradient points to
// higher values, i.e. inside, so the surface normal is its negation. A zero gradient (flat
// plateau exactly at the iso-value) falls back to `fallback`, which the caller sets to the
// edge direction from its inside to its outside corner.
LW_HOST_DEVICE inline McVec3 mcOutwardNormal(McVec3 gradient, McVec3 fallback) {
    const float len2 = gradient.x * gradient.x + gradient.y * gradient.y + gradient.z * gradient.z;
    if (!(len2 > 0.0f) || !std::isfinite(len2))
        return fallback;
    const float inv = -1.0f / std::sqrt(len2);
    return {gradient.x * inv, gradient.y * inv, gradient.z * inv};
}

// Inside bits of the voxel column (x,y,z), (x,y+1,z), (x,y,z+1), (x,y+1,z+1) starting at voxel
// `index`, for kMcColumnSpread; `inside(i)` classifies voxel i (each caller compares in the way
// that is fastest for its voxel type; all agree with mcInside).
template <typename Inside>
LW_HOST_DEVICE inline int mcColumnBits(const Inside& inside, std::size_t index, std::size_t sy,
                                       std::size_t sz) {
    return int(inside(index)) | int(inside(index + sy)) << 1 | int(inside(index + sz)) << 2 |
           int(inside(index + sy + sz)) << 3;
}

// Case of a cell from the columns (mcColumnBits) at its lower-x and upper-x voxels.
LW_HOST_DEVICE inline int mcCaseFromColumns(int lower, int upper) {
    return kMcColumnSpread.lower[lower] | kMcColumnSpread.upper[upper];
}

// Where the voxel grid lies in patient space, as plain values a kernel can take by value: grid
// point (x, y, k) sits at origin + x * stepI + y * stepJ + sliceOffset[k] * stack (mm).
struct McGridFrame {
    double origin[3], stepI[3], stepJ[3], stack[3];
    const double* sliceOffset; // per slice, along stack (uneven gaps allowed)
    // Row-major M^-T with M = (axisI, axisJ, stackAxis): turns a gradient in the oblique frame
    // into the patient gradient.
    float normalMatrix[9];
    // Patient direction of the +x/+y/+z edges (+z along increasing offsets): the normal of a
    // flat plateau exactly at the iso-value, see mcOutwardNormal.
    McVec3 edgeDirection[3];
    // Length (mm) of the +x and +y edges, |stepI| and |stepJ|: see mcAgreeWithEdge.
    float edgeLength[2];
    // Slab edges at least this long (units of slice offset, mm) always take their own difference
    // as the normal's component along them: see mcThickSlabEdge. Infinity on isotropic grids.
    float thickSlabEdge;
};

// How many times the finer in-plane spacing a slab edge must be long before its own difference
// replaces the central difference along it (see mcThickSlabEdge).
inline constexpr float kThickSlabOverPixel = 2.0f;

// The surface crosses an edge from its inside end to its outside end, so the field falls along
// that direction somewhere on the edge, and the outward normal there has a positive component
// along it. The gradient interpolated from central differences can say the opposite where the
// structure is thinner than a voxel (a plastic plate seen edge-on, the rim of a hole in it): the
// neighbours two voxels apart outweigh the edge. Then every normal of a small closed bit of
// surface may face the same way, n.v turns nowhere on it, and no method finds its contour (the
// outline of the bit goes undrawn). Where the interpolated gradient's component along the edge
// (the oblique frame's component `axis`: the derivative along the edge, per mm for i and j, per
// unit of slice offset for k) disagrees in sign with the edge's own difference, that difference
// replaces it. Elsewhere nothing changes, so smooth surfaces keep their normals bit for bit.
//
// `always` takes the edge's difference whatever the signs (mcThickSlabEdge).
LW_HOST_DEVICE inline void mcAgreeWithEdge(int axis, float a, float b, float run, bool always,
                                           McVec3& gradient) {
    // `run`: the edge's length in the derivative's units, negative for slices stored against the
    // stack axis. The component is picked by value and written back by branch, not through a
    // reference to a member chosen at run time: that would give the vector an address and push
    // it out of a GPU thread's registers (method 2 runs this for every surface cell and view).
    if (run == 0.0f)
        return;
    const float along = axis == 0 ? gradient.x : (axis == 1 ? gradient.y : gradient.z);
    const bool rises = (b > a) == (run > 0.0f); // the field rises along the axis
    if (!always && (along > 0.0f ? rises : (along < 0.0f && !rises)))
        return; // the common case: consistent (0 or NaN is replaced)
    const float slope = (b - a) / run;
    if (axis == 0)
        gradient.x = slope;
    else if (axis == 1)
        gradient.y = slope;
    else
        gradient.z = slope;
}

// On thick slices the central difference across slabs spans two slabs (10 mm on a 5 mm series),
// wider than a skull's bone: the normal's slab component lags behind the surface that marching
// cubes places on the edge, n.v turns away from where the mesh turns, and the contour of a
// surface that meets the slabs at a slant (the skull cap seen from below or the side) falls on
// the far side of the mesh's own outline, where the visibility test hides it. The edge's own
// difference is the exact derivative of the trilinear field along the edge, and with the
// in-plane central differences (the mean of the four cells' trilinear derivatives across the
// edge) the normal is that field's gradient averaged over the cells that share the vertex.
// In-plane edges keep the central differences: they span a millimetre and are smoother on
// noisy data. Isotropic grids do not use the rule at all, so their normals are unchanged.
LW_HOST_DEVICE inline bool mcThickSlabEdge(const McGridFrame& frame, int axis, float run) {
    return axis == 2 && (run < 0.0f ? -run : run) >= frame.thickSlabEdge;
}

struct McVertex {
    McVec3 position; // patient mm
    McVec3 normal;   // unit, outward
};

// The marching-cubes vertex on the edge that leaves voxel (x, y, z) along `axis`: `a`/`b` are the
// values and `ga`/`gb` the gradients (oblique frame, see VoxelGradientSampler) at its lower and
// upper voxel. Marching cubes and method 2 both place their vertices here, bit-identically.
LW_HOST_DEVICE LW_FORCE_INLINE McVertex mcEdgeVertex(const McGridFrame& frame, int x, int y, int z,
                                                     int axis, float a, float b, const McVec3& ga,
                                                     const McVec3& gb, double iso, float isoF) {
    const float t = mcEdgeParameter(a, b, iso);
    const double offset0 = frame.sliceOffset[z];
    const double offset1 = axis == 2 ? frame.sliceOffset[z + 1] : offset0;
    McVec3 gradient = mcLerp(ga, gb, t);
    const float run = axis == 2 ? float(offset1 - offset0)
                                : (axis == 0 ? frame.edgeLength[0] : frame.edgeLength[1]);
    mcAgreeWithEdge(axis, a, b, run, mcThickSlabEdge(frame, axis, run), gradient);
    const McVec3 g = mcTransform(frame.normalMatrix, gradient);
    McVec3 fallback = frame.edgeDirection[axis];
    if (!mcInside(a, isoF))
        fallback = {-fallback.x, -fallback.y, -fallback.z};
    McVertex vertex;
    vertex.normal = mcOutwardNormal(g, fallback);

    double px = x, py = y;
    double offset = offset0;
    if (axis == 0)
        px += t;
    else if (axis == 1)
        py += t;
    else
        offset += double(t) * (offset1 - offset);
    double p[3];
    for (int c = 0; c < 3; ++c)
        p[c] =
            frame.origin[c] + px * frame.stepI[c] + py * frame.stepJ[c] + offset * frame.stack[c];
    vertex.position = {float(p[0]), float(p[1]), float(p[2])};
    return vertex;
}

} // namespace lw::kernels
