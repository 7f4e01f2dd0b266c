#include "lw/render/surface_derivatives.h"

#include "lw/core/parallel.h"
#include "lw/kernels/cpu/marching_cubes_cpu.h"
#include "lw/kernels/cpu/voxel_ray.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace lw::render {
namespace {

// Gradient and Hessian of one volume's field at patient points, trilinear between grid points.
template <typename T> class FieldProbe {
public:
    FieldProbe(const volume::Volume& volume, kernels::GradientStencil stencil)
        : m_setup(kernels::cpu::voxelGridSetup(volume, stencil)),
          m_grid(volume), m_sampler{volume.dataAs<T>(), m_setup.spans()} {}

    // The volume's border planes the point lies in: bit 2a for index 0 along axis a, 2a + 1 for
    // the last index (within 1e-3 voxel).
    int borderPlanes(glm::dvec3 patient) const {
        const kernels::GridDims& d = m_setup.spans().dims;
        const glm::dvec3 index = m_grid.fractionalIndex(patient);
        const int last[3] = {d.cx, d.cy, d.cz};
        int planes = 0;
        for (int a = 0; a < 3; ++a) {
            planes |= std::abs(index[a]) < 1e-3 ? 1 << (2 * a) : 0;
            planes |= std::abs(index[a] - last[a]) < 1e-3 ? 1 << (2 * a + 1) : 0;
        }
        return planes;
    }

    void at(glm::dvec3 patient, glm::vec3& gradient, kernels::Sym3& hessian) const {
        const kernels::GridDims& d = m_setup.spans().dims;
        const glm::dvec3 index = m_grid.fractionalIndex(patient);
        int base[3];
        double frac[3];
        const int cells[3] = {d.cx, d.cy, d.cz};
        for (int a = 0; a < 3; ++a) {
            // The cell holding the point (the last cell for a point on the far face).
            const int last = std::max(0, cells[a] - 1);
            base[a] = std::clamp(int(std::floor(index[a])), 0, last);
            frac[a] = cells[a] > 0 ? std::clamp(index[a] - base[a], 0.0, 1.0) : 0.0;
        }
        kernels::McVec3 g{0, 0, 0};
        kernels::Sym3 h;
        for (int corner = 0; corner < 8; ++corner) {
            double weight = 1.0;
            int p[3];
            for (int a = 0; a < 3; ++a) {
                const bool upper = (corner >> a) & 1;
                weight *= upper ? frac[a] : 1.0 - frac[a];
                p[a] = std::min(base[a] + int(upper), cells[a]);
            }
            // A marching-cubes vertex lies on an edge: only its two ends carry weight.
            if (weight < 1e-7)
                continue;
            accumulate(float(weight), p[0], p[1], p[2], g, h);
        }
        const kernels::McVec3 gp = kernels::mcTransform(m_setup.frame().normalMatrix, g);
        gradient = {gp.x, gp.y, gp.z};
        hessian = kernels::hessianToPatient(m_setup.frame().normalMatrix, h);
    }

private:
    void accumulate(float weight, int x, int y, int z, kernels::McVec3& g, kernels::Sym3& h) const {
        const kernels::McVec3 cg = m_sampler.gradient(x, y, z);
        const kernels::Sym3 ch = kernels::frameHessian(m_sampler, x, y, z);
        g.x += weight * cg.x;
        g.y += weight * cg.y;
        g.z += weight * cg.z;
        h.xx += weight * ch.xx;
        h.yy += weight * ch.yy;
        h.zz += weight * ch.zz;
        h.xy += weight * ch.xy;
        h.xz += weight * ch.xz;
        h.yz += weight * ch.yz;
    }

    kernels::VoxelGridSetup m_setup;
    kernels::cpu::VoxelRayGrid m_grid; // patient point -> continuous voxel index
    kernels::VoxelGradientSampler<T> m_sampler;
};

template <typename F>
void withProbe(const volume::Volume& volume, kernels::GradientStencil stencil, F&& f) {
    switch (volume.voxelType()) {
    case volume::VoxelType::UInt8:
        return f(FieldProbe<std::uint8_t>(volume, stencil));
    case volume::VoxelType::Int16:
        return f(FieldProbe<std::int16_t>(volume, stencil));
    case volume::VoxelType::UInt16:
        return f(FieldProbe<std::uint16_t>(volume, stencil));
    case volume::VoxelType::Float32:
        break;
    }
    return f(FieldProbe<float>(volume, stencil));
}

// A triangle lying in one border plane of the grid belongs to the cap that closes the surface
// where the volume's border cuts it (border_cap_cpu.h; marching cubes' own triangles never lie
// in a face of the grid). The surface there is the flat cut face: gradient along the vertex's
// normal (the face's), Hessian 0, so kappa_r is 0 over the cap and draws nothing across it. The
// cap's vertices repeat the border's, with the face's normal, and belong to cap triangles only.
template <typename Probe>
void flattenBorderCaps(const Probe& probe, const kernels::TriangleMesh& mesh,
                       SurfaceDerivatives& out) {
    std::vector<int> planes(mesh.vertexCount(), -1); // -1: not looked up yet
    const auto planesOf = [&](std::uint32_t v) {
        if (planes[v] < 0)
            planes[v] = probe.borderPlanes(glm::dvec3(mesh.positions[v]));
        return planes[v];
    };
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const std::uint32_t* v = &mesh.indices[3 * t];
        if ((planesOf(v[0]) & planesOf(v[1]) & planesOf(v[2])) == 0)
            continue;
        for (int i = 0; i < 3; ++i) {
            const float length = glm::length(out.gradient[v[i]]);
            out.gradient[v[i]] = -mesh.normals[v[i]] * (length > 0.0f ? length : 1.0f);
            out.hessian[v[i]] = kernels::Sym3{};
        }
    }
}

} // namespace

SurfaceDerivatives surfaceDerivatives(const volume::Volume& volume,
                                      const kernels::TriangleMesh& mesh, unsigned threads,
                                      kernels::GradientStencil stencil) {
    SurfaceDerivatives out;
    const std::size_t count = mesh.vertexCount();
    out.gradient.resize(count);
    out.hessian.resize(count);
    constexpr std::size_t kChunk = 4096;
    withProbe(volume, stencil, [&](const auto& probe) {
        core::parallelForRanges(
            count, kChunk,
            [&](std::size_t begin, std::size_t end) {
                for (std::size_t v = begin; v < end; ++v)
                    probe.at(glm::dvec3(mesh.positions[v]), out.gradient[v], out.hessian[v]);
            },
            threads);
        flattenBorderCaps(probe, mesh, out);
    });
    return out;
}

} // namespace lw::render
