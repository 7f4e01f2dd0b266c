#pragma once

// Burns' silhouette segments of a host mesh (kernels/common/silhouette_segment.h), for the pieces
// a method adds to what its kernels find (the border cap of method 2).

#include "lw/kernels/silhouette_segment.h"
#include "lw/render/iso_surface.h"

#include <glm/glm.hpp>
#include <vector>

namespace lw::render {

// Appends the segment of every triangle of `mesh` that holds one, in triangle order.
// `eyeOrDirection`: the eye (perspective) or the unit vector toward the viewer (orthographic),
// rounded to float as the kernels round it.
void appendMeshSilhouette(const Mesh& mesh, glm::vec3 eyeOrDirection, bool orthographic,
                          std::vector<kernels::SegmentEndpoints>& out);

} // namespace lw::render
