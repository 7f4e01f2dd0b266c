#pragma once

// Shape-based interpolation across thick slices (Raya & Udupa 1990; Herman et al. 1992): the
// field between slices is the signed distance, within each slice, to that slice's iso contour,
// not the grey values.
//
// Why grey values cannot do it: where a smooth wall (the top of a skull) runs at a shallow angle
// to thick slices, each slice cuts it in a ring, the rings lying many pixels apart. A column of
// voxels between ring k + 1 and ring k sees bone in slice k and soft tissue in slice k + 1 --
// the same two values all across the band -- so any interpolation along the column (linear,
// cubic, smoothed) puts the surface at the same height across the whole band: a flat tread, then
// a riser at the next ring. Those risers are the terraces, and each draws a contour line. The
// in-plane distance to the contour does differ across the band: +a in slice k, -b in slice k + 1
// for a column a inside ring k and b outside ring k + 1, so interpolating it crosses zero at
// a / (a + b) of the gap -- the surface runs straight from ring to ring, as the anatomy does.
//
//      slice k    ####|####....      # inside (HU >= iso), . outside, | the contour
//      slice k+1  ##|######....      the band between the two contours: a tread under linear
//                                    interpolation, a slope under the distances
//
// The distance is exact to the sub-pixel contour: the contour points are where the grey values
// cross the iso-value along the rows and columns (where linear interpolation puts them, so within
// a slice the contour is where it was), and each pixel takes the nearest of them, in millimetres
// (anisotropic pixels count). It is found separably -- within a row the nearest row crossing is the
// one nearest along the row, then the minimum over the rows within the limit's reach, and the
// same for the columns -- so it costs the slice's size times the reach in pixels, and it is the
// exact minimum, which a GPU that searches a window instead finds too, bit for bit
// (kernels/slice_field_rules.h; kernels/cuda/thick_slice_field_cuda.h). The result depends on
// the iso-value: a new iso-value needs a new field.
//
// Distances are limited to +-limitMm, and a slice with no contour at all is at the limit
// throughout. The limit says how far beyond the last slice that shows a structure it may reach:
// between a slice where a tube's top still shows (+a at its centre) and the next, where nothing
// does, the surface closes a / (a + limit) of the way across -- at the slice itself without a
// limit, a flat cap. One slice step (what the rendering uses) lets partial volume show as it does
// between two slices; bands wider than two steps (the flattest part of a skull cap) keep the
// slope near their rings and a level middle.

#include "lw/volume/volume.h"

namespace lw::volume {

// The signed distance volume's stored units: 1/kSliceDistanceStepsPerMm mm.
inline constexpr double kSliceDistanceStepsPerMm = 128.0;

// Per slice of `volume`, the signed in-plane distance (mm, positive where the real value is at
// least `iso`, within +-limitMm) to the iso contour, as an int16 volume of the same dims and
// geometry whose value mapping gives iso + distance: drawn at `iso`, its surface is the
// contours' in every slice, and between slices it follows the shape-based interpolation.
// Description kept. Throws core::Error for a limit outside (0, 255] mm, or, before allocating,
// for a copy larger than `limits` allows.
Volume signedSliceDistance(const Volume& volume, double iso, double limitMm, unsigned threads = 0,
                           const core::ImportLimits& limits = {});

// The same distances written into an int16 `field` of the volume's in-plane size and
// (dims.z - 1) * sliceStep + 1 slices: slice k into slice k * sliceStep, the others left as they
// are (for refineBetweenSlices, volume/oversampling.h, to fill -- the thick-slice field in one
// volume, without a copy between). The field's value mapping and description are left to the
// caller. Throws core::Error for a limit outside (0, 255] mm or a field of another size or type.
void writeSignedSliceDistance(const Volume& volume, double iso, double limitMm, int sliceStep,
                              Volume& field, unsigned threads = 0);

} // namespace lw::volume
