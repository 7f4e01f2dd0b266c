#pragma once

// Thick slices made from thin ones, as a scanner makes a thick reconstruction: each thick slice
// is the mean of `slicesPerSlab` neighbouring thin slices (the scanner integrates over the slab
// it reconstructs), placed at their mean position. A thin series and its thick version show the
// same anatomy, so the thin one's drawing is the reference the thick one's is measured against
// (`linework-cli thick-slices`).
//
//   thin   0 1 2 3 4 | 5 6 7 8 9 | 10 ...     slicesPerSlab = 5; a last partial slab is dropped
//   thick      0     |     1     |  ...       at the mean position of its five

#include "lw/volume/volume.h"

namespace lw::evaluation {

// Throws core::Error when fewer than two whole slabs fit or slicesPerSlab < 1. Integer voxel
// types are rounded to the nearest value; the value mapping and description are kept, the
// in-plane geometry and a gantry tilt too, and uneven thin gaps give uneven thick ones.
volume::Volume thickSlabsOf(const volume::Volume& thin, int slicesPerSlab);

// The same slab means, but a slab starting at every thin slice (the thin spacing kept, the
// first and last slicesPerSlab / 2 slices' positions dropped): what the thick slabs hold,
// sampled as densely as the thin series. Drawn with straight lines between its slices, it is
// the bound on what any interpolation between the thick slices can show -- a structure the
// slab mean dilutes below the iso-value is gone from every thick slice too -- so a thick
// drawing's recall against the thin one is read against this one's (`thick-slices --bound`).
//
//   thin       0 1 2 3 4 5 6 7 8 ...   slicesPerSlab = 5
//   thick          0    |    1        (slabs 0-4, 5-9)
//   every slice    0 1 2 3 4 ...      (slabs 0-4, 1-5, 2-6, ...)
volume::Volume slabMeansAtEverySlice(const volume::Volume& thin, int slicesPerSlab);

// Scanner-like noise for the line-quality measures: independent Gaussian noise of `sigma` real
// units (HU for CT) added to every voxel, from a fixed seed, so a run is repeatable (integer
// voxels rounded and clamped to their type's range). The noise of a sharp (bone) kernel is
// close to white at the voxel scale; a thin series so noised stands in for a bone-kernel scan.
// Throws core::Error for a negative sigma.
void addVoxelNoise(volume::Volume& volume, double sigma, unsigned seed = 1);

} // namespace lw::evaluation
