#include "lw/kernels/cpu/border_cap_cpu.h"

#include "lw/kernels/cpu/marching_cubes_cpu.h"
#include "lw/kernels/marching_cubes.h"

#include <array>
#include <cstdint>
#include <unordered_map>

namespace lw::kernels::cpu {
namespace {

// The six faces of the volume, low and high side per axis: face 2 * axis + (high ? 1 : 0).
using FaceFlags = std::array<bool, 6>;

template <typename T> class CapBuilder {
public:
    CapBuilder(const volume::Volume& volume, double iso, GradientStencil stencil)
        : m_voxels(volume.dataAs<T>()), m_dims(makeGridDims(volume.dims())), m_iso(iso),
          m_isoF(insideThreshold(iso)), m_threshold(voxelInsideThreshold<T>(iso)),
          m_grid(voxelGridSetup(volume, stencil)), m_gradient{m_voxels, m_grid.spans()} {
        setFaceNormals();
    }

    TriangleMesh build() {
        const FaceFlags faces = facesWithInside();
        const int cx = m_dims.cx, cy = m_dims.cy, cz = m_dims.cz;
        // Padded cells (i, j, k), i in [-1, cx] (cell i spans voxels i .. i+1), in cell order;
        // the shell is every cell with a padded corner. A shell cell's real corners lie on the
        // face(s) its shell coordinate names, so a face without an inside voxel skips them.
        for (int k = -1; k <= cz; ++k) {
            const bool kShell = k == -1 || k == cz;
            if (kShell && !faces[k == -1 ? 4 : 5])
                continue;
            for (int j = -1; j <= cy; ++j) {
                const bool jShell = j == -1 || j == cy;
                if (kShell || jShell) {
                    if (!kShell && !faces[j == -1 ? 2 : 3])
                        continue;
                    for (int i = -1; i <= cx; ++i)
                        emitCell(i, j, k);
                } else {
                    if (faces[0])
                        emitCell(-1, j, k);
                    if (faces[1])
                        emitCell(cx, j, k);
                }
            }
        }
        return std::move(m_mesh);
    }

private:
    bool real(int x, int y, int z) const {
        return x >= 0 && x < m_dims.nx && y >= 0 && y < m_dims.ny && z >= 0 && z < m_dims.nz;
    }
    std::size_t index(int x, int y, int z) const {
        return std::size_t(x) + m_dims.sy * std::size_t(y) + m_dims.sz * std::size_t(z);
    }
    bool inside(int x, int y, int z) const {
        return real(x, y, z) && m_voxels[index(x, y, z)] >= m_threshold;
    }

    FaceFlags facesWithInside() const {
        FaceFlags faces{};
        const int nx = m_dims.nx, ny = m_dims.ny, nz = m_dims.nz;
        for (int z = 0; z < nz; ++z)
            for (int y = 0; y < ny; ++y) {
                faces[0] = faces[0] || inside(0, y, z);
                faces[1] = faces[1] || inside(nx - 1, y, z);
                if (y == 0 || y == ny - 1 || z == 0 || z == nz - 1)
                    for (int x = 0; x < nx; ++x) {
                        const bool in = inside(x, y, z);
                        faces[2] = faces[2] || (in && y == 0);
                        faces[3] = faces[3] || (in && y == ny - 1);
                        faces[4] = faces[4] || (in && z == 0);
                        faces[5] = faces[5] || (in && z == nz - 1);
                    }
            }
        return faces;
    }

    // Outward unit normal of each face: the padded gradient at a pad -> real edge is the pad
    // step along the axis (oblique frame; along the stack axis its sign follows the slice
    // order), mapped to patient space like every marching-cubes gradient.
    void setFaceNormals() {
        const std::vector<double>& offsets = m_grid.sliceOffsets();
        const float stackSign = offsets.back() - offsets.front() >= 0.0 ? 1.0f : -1.0f;
        for (int axis = 0; axis < 3; ++axis) {
            McVec3 step{0.0f, 0.0f, 0.0f};
            (axis == 0 ? step.x : (axis == 1 ? step.y : step.z)) = axis == 2 ? stackSign : 1.0f;
            const McVec3 g = mcTransform(m_grid.frame().normalMatrix, step);
            const McVec3 none{0.0f, 0.0f, 0.0f};
            // Values rise from the low face's pad into the volume and fall into the high one's.
            m_faceNormal[2 * axis] = mcOutwardNormal(g, none);
            m_faceNormal[2 * axis + 1] = mcOutwardNormal({-g.x, -g.y, -g.z}, none);
        }
    }

    void emitCell(int i, int j, int k) {
        int cubeCase = 0;
        for (int c = 0; c < 8; ++c)
            cubeCase |= int(inside(i + kMcCornerOffset[c][0], j + kMcCornerOffset[c][1],
                                   k + kMcCornerOffset[c][2]))
                        << c;
        if (cubeCase == 0)
            return;
        const std::int8_t* edges = kMcTriTable[cubeCase];
        for (int e = 0; edges[e] >= 0; ++e) {
            const std::int8_t* owner = kMcEdgeOwner[edges[e]];
            m_mesh.indices.push_back(vertexId(i + owner[0], j + owner[1], k + owner[2], owner[3]));
        }
    }

    // The id of the vertex on the edge leaving (padded) voxel (x, y, z) along `axis`.
    std::uint32_t vertexId(int x, int y, int z, int axis) {
        const std::uint64_t key =
            ((std::uint64_t(z + 1) * std::uint64_t(m_dims.ny + 2) + std::uint64_t(y + 1)) *
                 std::uint64_t(m_dims.nx + 2) +
             std::uint64_t(x + 1)) *
                3 +
            std::uint64_t(axis);
        const auto [it, isNew] = m_ids.try_emplace(key, std::uint32_t(m_mesh.positions.size()));
        if (isNew) {
            const McVertex v = edgeVertex(x, y, z, axis);
            m_mesh.positions.emplace_back(v.position.x, v.position.y, v.position.z);
            m_mesh.normals.emplace_back(v.normal.x, v.normal.y, v.normal.z);
        }
        return it->second;
    }

    McVertex edgeVertex(int x, int y, int z, int axis) const {
        const int ux = x + (axis == 0), uy = y + (axis == 1), uz = z + (axis == 2);
        if (real(x, y, z) && real(ux, uy, uz)) // in the border plane: marching cubes' vertex
            return m_gradient.edgeVertex(m_grid.frame(), x, y, z, axis,
                                         m_gradient.gradient(x, y, z),
                                         m_gradient.gradient(ux, uy, uz), m_iso, m_isoF);
        // One end is padding, the other the inside voxel the crossing sits on.
        const bool lowerIsPad = !real(x, y, z);
        const int rx = lowerIsPad ? ux : x, ry = lowerIsPad ? uy : y, rz = lowerIsPad ? uz : z;
        const McGridFrame& f = m_grid.frame();
        const double px = rx, py = ry, offset = f.sliceOffset[rz];
        McVertex v;
        double p[3];
        for (int c = 0; c < 3; ++c) // the expression mcEdgeVertex evaluates at t = 0
            p[c] = f.origin[c] + px * f.stepI[c] + py * f.stepJ[c] + offset * f.stack[c];
        v.position = {float(p[0]), float(p[1]), float(p[2])};
        v.normal = m_faceNormal[2 * axis + (lowerIsPad ? 0 : 1)];
        return v;
    }

    const T* m_voxels;
    GridDims m_dims;
    double m_iso;
    float m_isoF;
    T m_threshold;
    VoxelGridSetup m_grid;
    VoxelGradientSampler<T> m_gradient;
    McVec3 m_faceNormal[6]{};
    std::unordered_map<std::uint64_t, std::uint32_t> m_ids;
    TriangleMesh m_mesh;
};

} // namespace

TriangleMesh borderCap(const volume::Volume& volume, double storedIso, GradientStencil stencil) {
    const glm::ivec3 d = volume.dims();
    if (d.x < 1 || d.y < 1 || d.z < 1)
        return {};
    return volume::dispatchVoxelType(volume.voxelType(), [&](auto tag) {
        using T = decltype(tag);
        return CapBuilder<T>(volume, storedIso, stencil).build();
    });
}

void appendMesh(TriangleMesh& mesh, const TriangleMesh& piece) {
    const auto base = std::uint32_t(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), piece.positions.begin(), piece.positions.end());
    mesh.normals.insert(mesh.normals.end(), piece.normals.begin(), piece.normals.end());
    mesh.indices.reserve(mesh.indices.size() + piece.indices.size());
    for (const std::uint32_t i : piece.indices)
        mesh.indices.push_back(base + i);
}

} // namespace lw::kernels::cpu
