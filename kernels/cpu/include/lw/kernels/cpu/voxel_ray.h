#pragma once

// A 3D DDA through the cells of a volume's grid, for the ray-cast visibility test of method 2:
// the host owner of the slice table behind kernels/common's RayGridView (voxel_ray_walk.h), which
// holds the stepping rules shared with the CUDA back-end.

#include "lw/kernels/voxel_ray_walk.h"
#include "lw/volume/volume.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <glm/glm.hpp>
#include <limits>
#include <vector>

namespace lw::kernels::cpu {

using kernels::CellExit;

class VoxelRayGrid {
public:
    VoxelRayGrid() = default;
    explicit VoxelRayGrid(const volume::Volume& volume) {
        const auto& g = volume.geometry();
        m_dims = volume.dims();
        m_origin = g.origin();
        m_offsets.resize(std::size_t(std::max(m_dims.z, 1)));
        for (int k = 0; k < m_dims.z; ++k)
            m_offsets[std::size_t(k)] = g.sliceOffset(double(k));
        glm::dvec3 stack = g.stackAxis();
        // Slices stored against the stack direction: flip s so the walls increase with k.
        if (m_dims.z > 1 && m_offsets.back() < m_offsets.front()) {
            stack = -stack;
            for (double& o : m_offsets)
                o = -o;
        }
        const glm::dmat3 frame(g.spacingI() * g.axisI(), g.spacingJ() * g.axisJ(), stack);
        m_toGrid = glm::inverse(frame);
        m_toPatient = frame;
        m_refinement = g.refinement();
    }

    glm::ivec3 dims() const { return m_dims; }
    glm::ivec3 cellCount() const { return glm::max(m_dims - 1, glm::ivec3(0)); }
    glm::dvec3 toGrid(glm::dvec3 patient) const { return m_toGrid * (patient - m_origin); }
    glm::dvec3 directionToGrid(glm::dvec3 patientDirection) const {
        return m_toGrid * patientDirection;
    }
    glm::dvec3 toPatient(glm::dvec3 grid) const { return m_origin + m_toPatient * grid; }
    // Continuous voxel index (i, j, k) of a patient point: the inverse of indexToPatient, the
    // slice index piecewise linear between the slices (uneven gaps); outside the stack it goes
    // on linearly from the first or last slab.
    glm::dvec3 fractionalIndex(glm::dvec3 patient) const {
        const glm::dvec3 u = toGrid(patient);
        if (m_offsets.size() < 2)
            return {u.x, u.y, 0.0};
        const std::ptrdiff_t above =
            std::upper_bound(m_offsets.begin(), m_offsets.end(), u.z) - m_offsets.begin();
        const int k =
            int(std::clamp<std::ptrdiff_t>(above - 1, 0, std::ptrdiff_t(m_offsets.size()) - 2));
        return {u.x, u.y, double(k) + sliceFraction(u.z, k)};
    }
    double offset(int k) const { return m_offsets[std::size_t(k)]; }
    // Fractional slice index of grid coordinate s inside slab k (k .. k+1).
    double sliceFraction(double s, int k) const {
        const double gap = m_offsets[std::size_t(k) + 1] - m_offsets[std::size_t(k)];
        return gap > 0.0 ? (s - m_offsets[std::size_t(k)]) / gap : 0.0;
    }

    // The plain view the walk and the CUDA kernels use (points into this object).
    kernels::RayGridView view() const {
        kernels::RayGridView v;
        v.dims = m_dims;
        v.origin = m_origin;
        v.toGrid = m_toGrid;
        v.offsets = m_offsets.data();
        v.offsetCount = int(m_offsets.size());
        const double span = m_offsets.back() - m_offsets.front();
        if (m_offsets.size() > 1 && span > 0.0)
            v.slabGuessScale = double(m_offsets.size() - 1) / span;
        return v;
    }
    // Slice offsets after the flip described above (increasing).
    const std::vector<double>& offsets() const { return m_offsets; }
    // Cell widths in grid units (i, j, s): the mean slab thickness along s. The visibility rule
    // measures its self-occlusion distances in these units.
    glm::dvec3 cellScale() const {
        const double s =
            m_dims.z > 1 ? std::abs(m_offsets.back() - m_offsets.front()) / (m_dims.z - 1) : 1.0;
        return glm::dvec3(1.0, 1.0, s > 0.0 ? s : 1.0);
    }

    // How many times its pixels' width a slab is thick (the mean slab against the finer
    // in-plane spacing).
    double slabOverPixel() const {
        const double pixel = std::min(glm::length(m_toPatient[0]), glm::length(m_toPatient[1]));
        return pixel > 0.0 ? cellScale().z / pixel : 1.0;
    }

    // The neighbour ray's reach (neighbourReachCells) on this grid: how many of its finest cells
    // the coarsest cell of the grid it was sampled from spans, since the terraces of a coarse
    // axis are as deep as its cells. A thick-slice series: its slab against its pixel
    // (slabOverPixel); a grid coarse in plane and fine across slices (VTK's quarter head, 3.2 mm
    // pixels on 1.5 mm slices): its pixel against its slab. An oversampled volume
    // (volume/oversampling.h) holds the field of its original grid: `refinement` of its cells
    // make one of the original's, so the reach counts those.
    double neighbourReach() const {
        const glm::dvec3 cell(glm::length(m_toPatient[0]), glm::length(m_toPatient[1]),
                              cellScale().z);
        const double finest = std::min({cell.x, cell.y, cell.z});
        const double coarsestOriginal =
            std::max({cell.x * m_refinement.x, cell.y * m_refinement.y, cell.z * m_refinement.z});
        return neighbourReachCells(finest > 0.0 ? coarsestOriginal / finest : 1.0);
    }

    // RayGridView::cellOf and ::walk (voxel_ray_walk.h).
    bool cellOf(glm::dvec3 u, glm::dvec3 direction, glm::ivec3& cell) const {
        return view().cellOf(u, direction, cell);
    }
    template <typename OnExit>
    bool walk(glm::dvec3 start, glm::dvec3 direction, double tMax, OnExit&& onExit) const {
        return view().walk(start, direction, tMax, onExit);
    }

private:
    glm::ivec3 m_dims{0};
    glm::dvec3 m_origin{0.0};
    glm::dmat3 m_toGrid{1.0};
    glm::dmat3 m_toPatient{1.0};
    std::vector<double> m_offsets{0.0};
    glm::ivec3 m_refinement{1}; // volume::VolumeGeometry::refinement()
};

} // namespace lw::kernels::cpu
