#include "lw/kernels/cpu/border_cap_cpu.h"

#include "lw/core/parallel.h"
#include "lw/kernels/cpu/marching_cubes_cpu.h"
#include "lw/kernels/marching_cubes.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>
#include <utility>
#include <vector>

namespace lw::kernels::cpu {
namespace {

// The six faces of the volume, low and high side per axis: face 2 * axis + (high ? 1 : 0).
using FaceFlags = std::array<bool, 6>;

// The cap's vertex ids by edge: open addressing with linear probing, doubled at half full (a
// cap of the demo has 20 700 vertices; std::unordered_map allocated a node for each). An edge is
// named by its voxel row ((z + 1) * (ny + 2) + y + 1 in the padded volume) and its place along
// it (3 * (x + 1) + axis): a row's edges go to consecutive slots from a scattered start, so that
// neighbouring cells' edges share cache lines.
class VertexIdMap {
public:
    // The id kept for the edge, or `fresh` kept for it now (second: whether it was new).
    std::pair<std::uint32_t, bool> findOrInsert(std::uint64_t row, std::uint32_t along,
                                                std::uint32_t fresh) {
        if ((m_count + 1) * 2 > m_slots.size())
            grow();
        Slot& slot = probe(m_slots, row, along);
        if (slot.row == row && slot.along == along)
            return {slot.id, false};
        slot = {row, along, fresh};
        ++m_count;
        return {fresh, true};
    }

private:
    // Never a row: rows number the padded volume's voxel rows, fewer than 2^64 - 1.
    static constexpr std::uint64_t kEmpty = std::numeric_limits<std::uint64_t>::max();
    struct Slot {
        std::uint64_t row = kEmpty;
        std::uint32_t along = 0;
        std::uint32_t id = 0;
    };

    // The slot holding the edge, or the empty one where it goes.
    static Slot& probe(std::vector<Slot>& slots, std::uint64_t row, std::uint32_t along) {
        const std::size_t mask = slots.size() - 1;
        const int bits = std::countr_zero(slots.size());
        const std::size_t start = std::size_t((row * 0x9E3779B97F4A7C15ull) >> (64 - bits));
        std::size_t at = (start + along) & mask;
        while (slots[at].row != kEmpty && !(slots[at].row == row && slots[at].along == along))
            at = (at + 1) & mask;
        return slots[at];
    }

    void grow() {
        std::vector<Slot> larger(std::max<std::size_t>(1024, m_slots.size() * 2));
        for (const Slot& slot : m_slots)
            if (slot.row != kEmpty)
                probe(larger, slot.row, slot.along) = slot;
        m_slots = std::move(larger);
    }

    std::vector<Slot> m_slots; // a power of two of them, or none
    std::size_t m_count = 0;
};

template <typename T> class CapBuilder {
public:
    CapBuilder(const volume::Volume& volume, double iso, GradientStencil stencil)
        : m_voxels(volume.dataAs<T>()), m_dims(makeGridDims(volume.dims())), m_iso(iso),
          m_isoF(insideThreshold(iso)), m_threshold(voxelInsideThreshold<T>(iso)),
          m_grid(voxelGridSetup(volume, stencil)), m_gradient{m_voxels, m_grid.spans()},
          m_insideColumns(std::size_t(m_dims.nx) + 2, 0) {
        setFaceNormals();
    }

    // The faces with an inside voxel.
    FaceFlags facesOf(const BorderFaceMaxima& maxima) const {
        FaceFlags faces{};
        for (std::size_t f = 0; f < faces.size(); ++f)
            faces[f] = maxima.value[f] >= double(m_threshold);
        return faces;
    }

    // The cap over `faces` (facesOf: those with an inside voxel, or fewer).
    TriangleMesh build(const FaceFlags& faces) {
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
                    emitCellRow(j, k);
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

    // The cells (i, j, k) of a whole shell row, i in [-1, cx], in order. Only cells with an
    // inside corner emit anything, so the walk covers just the columns from one left of the
    // first inside voxel to the last one, over the real voxel rows the cells' corners lie on,
    // and within that span only the cells with an inside corner (a skull cut by the first
    // slice is a ring; the span is the head's width). At a new iso-value of the demo
    // (512 x 512 x 82, 400 HU: 18 652 cells emit 37 264 triangles) the cap took 7.8 ms on dev-2c
    // testing 8 corners of every cell of the first and last slice, 3.2-3.6 ms over the span.
    void emitCellRow(int j, int k) {
        int first = m_dims.nx, last = -1;
        for (int y = std::max(j, 0); y <= std::min(j + 1, m_dims.ny - 1); ++y)
            for (int z = std::max(k, 0); z <= std::min(k + 1, m_dims.nz - 1); ++z)
                widenToInside(y, z, first, last);
        if (first > last)
            return; // no inside voxel: every cell of the row is empty
        markInsideColumns(j, k, first, last);
        // Cell i has an inside corner where column i or i + 1 has one: m_insideColumns[i + 1]
        // or [i + 2]. Eight cells at a time, in order.
        const std::uint8_t* columns = m_insideColumns.data();
        const int end = std::min(last, m_dims.cx) + 1;
        int i = first - 1;
        for (; i + 8 <= end; i += 8) {
            std::uint64_t here, next;
            std::memcpy(&here, columns + i + 1, 8);
            std::memcpy(&next, columns + i + 2, 8);
            for (std::uint64_t any = here | next; any != 0; any &= any - 1)
                emitCell(i + std::countr_zero(any) / 8, j, k); // little-endian: byte order
        }
        for (; i < end; ++i)
            if ((columns[i + 1] | columns[i + 2]) != 0)
                emitCell(i, j, k);
        std::fill(m_insideColumns.begin() + first + 1, m_insideColumns.begin() + last + 2, 0);
    }

    // m_insideColumns[x + 1] = 1 for x in [first, last] where a voxel row the cell row (j, k)'s
    // corners lie on is inside at x (the array is 0 elsewhere, and again after the row).
    void markInsideColumns(int j, int k, int first, int last) {
        std::uint8_t* columns = m_insideColumns.data() + 1;
        const T threshold = m_threshold;
        for (int y = std::max(j, 0); y <= std::min(j + 1, m_dims.ny - 1); ++y)
            for (int z = std::max(k, 0); z <= std::min(k + 1, m_dims.nz - 1); ++z) {
                const T* row = m_voxels + index(0, y, z);
                for (int x = first; x <= last; ++x)
                    columns[x] |= std::uint8_t(row[x] >= threshold);
            }
    }

    // [first, last] grown to cover the inside voxels of voxel row (y, z), a row on a face (the
    // only rows shell cells' corners lie on). Each row's range is found once: neighbouring cell
    // rows share a voxel row.
    void widenToInside(int y, int z, int& first, int& last) {
        RowRange& range = faceRowRange(y, z);
        if (range.first == kRowNotScanned.first)
            range = insideRange(m_voxels + index(0, y, z));
        first = std::min(first, range.first);
        last = std::max(last, range.last);
    }

    struct RowRange {
        int first, last;
    };
    static constexpr RowRange kRowNotScanned{-2, -2};

    // The memo of a face row: the first and last slice's rows by y, the first and last rows of
    // every slice by z.
    RowRange& faceRowRange(int y, int z) {
        const auto slot = [](std::vector<RowRange>& rows, int count, int at) -> RowRange& {
            if (rows.empty())
                rows.assign(std::size_t(count), kRowNotScanned);
            return rows[std::size_t(at)];
        };
        if (z == 0)
            return slot(m_faceRows[0], m_dims.ny, y);
        if (z == m_dims.nz - 1)
            return slot(m_faceRows[1], m_dims.ny, y);
        return slot(m_faceRows[y == 0 ? 2 : 3], m_dims.nz, z); // y is 0 or ny - 1
    }

    // The first and last inside voxel of a row ({nx, -1} when none is).
    RowRange insideRange(const T* row) const {
        int x = 0;
        while (x < m_dims.nx && !(row[x] >= m_threshold))
            ++x;
        if (x == m_dims.nx)
            return {m_dims.nx, -1};
        int end = m_dims.nx - 1;
        while (!(row[end] >= m_threshold))
            --end;
        return {x, end};
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
        const std::uint64_t row =
            std::uint64_t(z + 1) * std::uint64_t(m_dims.ny + 2) + std::uint64_t(y + 1);
        const auto along = std::uint32_t(3 * (x + 1) + axis);
        const auto [id, isNew] =
            m_ids.findOrInsert(row, along, std::uint32_t(m_mesh.positions.size()));
        if (isNew) {
            const McVertex v = edgeVertex(x, y, z, axis);
            m_mesh.positions.emplace_back(v.position.x, v.position.y, v.position.z);
            m_mesh.normals.emplace_back(v.normal.x, v.normal.y, v.normal.z);
        }
        return id;
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
    VertexIdMap m_ids;
    std::array<std::vector<RowRange>, 4> m_faceRows; // faceRowRange's memo
    std::vector<std::uint8_t> m_insideColumns;       // markInsideColumns', x + 1 for x in [-1, nx]
    TriangleMesh m_mesh;
};

} // namespace

BorderFaceMaxima borderFaceMaxima(const volume::Volume& volume) {
    const glm::ivec3 d = volume.dims();
    BorderFaceMaxima maxima;
    maxima.value.fill(-std::numeric_limits<double>::infinity());
    volume::dispatchVoxelType(volume.voxelType(), [&](auto tag) {
        using T = decltype(tag);
        const T* voxels = volume.dataAs<T>();
        const auto at = [&](int x, int y, int z) { return double(voxels[volume.index(x, y, z)]); };
        const auto widen = [&](std::size_t face, double value) {
            if (value > maxima.value[face]) // NaN never is
                maxima.value[face] = value;
        };
        for (int z = 0; z < d.z; ++z)
            for (int y = 0; y < d.y; ++y) {
                widen(0, at(0, y, z));
                widen(1, at(d.x - 1, y, z));
                if (y == 0 || y == d.y - 1 || z == 0 || z == d.z - 1)
                    for (int x = 0; x < d.x; ++x) {
                        const double value = at(x, y, z);
                        if (y == 0)
                            widen(2, value);
                        if (y == d.y - 1)
                            widen(3, value);
                        if (z == 0)
                            widen(4, value);
                        if (z == d.z - 1)
                            widen(5, value);
                    }
            }
    });
    return maxima;
}

TriangleMesh borderCap(const volume::Volume& volume, double storedIso, GradientStencil stencil,
                       const BorderFaceMaxima* faces) {
    const glm::ivec3 d = volume.dims();
    if (d.x < 1 || d.y < 1 || d.z < 1)
        return {};
    const BorderFaceMaxima maxima = faces ? *faces : borderFaceMaxima(volume);
    return volume::dispatchVoxelType(volume.voxelType(), [&](auto tag) {
        using T = decltype(tag);
        CapBuilder<T> builder(volume, storedIso, stencil);
        const FaceFlags inside = builder.facesOf(maxima);
        // The first and last slice alone hold inside voxels (a head in the field of view, cut
        // by the ends of the series): their caps share no edge (z in {-1, 0} and {nz - 1, nz}),
        // and the walk makes the first one's cells and vertices before any of the last one's,
        // so the two made side by side and joined are the same bytes.
        const bool slicesAlone = !inside[0] && !inside[1] && !inside[2] && !inside[3];
        if (!(slicesAlone && inside[4] && inside[5] && d.z >= 2))
            return builder.build(inside);
        std::array<TriangleMesh, 2> ends;
        core::parallelFor(2, [&](std::size_t end) {
            FaceFlags one{};
            one[4 + end] = true;
            ends[end] = end == 0 ? builder.build(one)
                                 : CapBuilder<T>(volume, storedIso, stencil).build(one);
        });
        appendMesh(ends[0], ends[1]);
        return std::move(ends[0]);
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
