#pragma once

// How finely the methods sample a volume's field: as loaded, or oversampled where its cells
// would come out large in the picture (volume/oversampling.h says why that matters and why the
// surface stays the same). The rule needs no view: the camera frames the whole volume, so a
// cell's share of the volume's diagonal is its share of the picture. Auto splits each axis
// until its cells are at most 1/kOversamplingCellsPerDiagonal of the diagonal (8 pixels of a
// 1024-pixel view), so coarse axes get finer and fine ones stay: a 5 mm series of a head gets
// 2.5 mm slabs, a 0.5 mm one nothing, and a refined axis never holds much more than 128
// samples, so the copy stays small.

#include "lw/volume/volume.h"

#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string_view>

namespace lw::render {

enum class Oversampling { Off, Auto };

inline constexpr double kOversamplingCellsPerDiagonal = 128.0;
inline constexpr int kMaxOversamplingFactor = 8;

std::string_view oversamplingName(Oversampling oversampling); // "off" | "auto"
std::optional<Oversampling> parseOversampling(std::string_view name);

// The factors along (i, j, k) that `oversampling` gives a volume of `dims` on `geometry`:
// (1, 1, 1) for Off, for a volume of one voxel along every axis, or when no cell is too large.
glm::ivec3 oversamplingFactors(glm::ivec3 dims, const volume::VolumeGeometry& geometry,
                               Oversampling oversampling);

// `volume` oversampled by oversamplingFactors (volume::oversampled; logged on lw.render), or
// nothing where the factors are all 1: the volume itself is the one to draw.
std::optional<volume::Volume> oversampledToRender(const volume::Volume& volume,
                                                  Oversampling oversampling, unsigned threads = 0);

// The volume the methods draw: `volume` itself where the factors are all 1, else its
// oversampled copy.
std::shared_ptr<const volume::Volume> volumeToRender(std::shared_ptr<const volume::Volume> volume,
                                                     Oversampling oversampling,
                                                     unsigned threads = 0);

} // namespace lw::render
