#pragma once

// Where method 1's whole mesh comes from. By default the CPU extracts it and uploadMesh() copies
// it through host memory; with the CUDA back-end (cuda/cuda_gl_mesh_source.cpp) marching cubes
// runs on the GPU and writes the GL buffers directly through CUDA-GL interop, no host round trip.

#include "lw/core/image.h"
#include "lw/render/camera.h"
#include "lw/render/iso_surface.h"
#include "lw/render/pixel_mask.h"
#include "lw/render/shaded_surface_cpu.h"
#include "lw/render/silhouette_gl_renderer.h"
#include "lw/render/silhouette_renderer.h"
#include "lw/volume/volume.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

namespace lw::render {

class GlMeshSource {
public:
    virtual ~GlMeshSource() = default;
    virtual std::string_view backendName() const = 0;
    virtual void setVolume(const volume::Volume& volume) = 0;
    // After setVolume: the bound voxels on the device already (SilhouetteRenderer::
    // setVolumeWithDeviceCopy), until the next setVolume. Only the CUDA source takes it.
    virtual void useDeviceCopy(DeviceVoxelCopy /*copy*/) {}
    // Extracts the surface at settings.isoReal into gl's mesh buffers (its context current).
    // Throws core::Error naming the failed step.
    virtual void extractInto(SilhouetteGlRenderer& gl, const SilhouetteSettings& settings) = 0;
    // The last extraction, on the host (for the iso panel's callers that want the mesh).
    virtual void download(Mesh& mesh) = 0;
    // Of the last whole extraction, only the triangles that may hold `camera`'s contour
    // (contour_triangles.h), selected on the source's device; nullopt where it has none.
    virtual std::optional<Mesh> contourTriangles(const Camera& /*camera*/) { return std::nullopt; }
    // Drops the strokes under `minPixels` from a mask read back from GL on the source's device,
    // as PixelMask::pruneStrokes(minPixels, gapPixels) would; false when the
    // source has no device or it failed (the host prunes then).
    virtual bool pruneStrokes(PixelMask& /*lines*/, int /*minPixels*/, int /*gapPixels*/) {
        return false;
    }
    // The iso panel of the last whole extraction (and its cap) lit on the source's device as
    // shadeSurfaceCpu lights the host mesh: `image` sized to the camera, `depth` (optional) as
    // there, `triangles` the surface's. False where the source has no device, its last
    // extraction was in pieces, or the device failed (said once; GL shades the panel then).
    virtual bool shadeWhole(const Camera& /*camera*/, const SurfaceShading& /*shading*/,
                            core::ImageRgba8& /*image*/, std::vector<float>* /*depth*/,
                            std::size_t& /*triangles*/) {
        return false;
    }
    // GL objects the source registered: released while the context is still current.
    virtual void releaseGl() = 0;
    // The chunked (L) variant on the source's device: the surface in pieces that fit its memory
    // budget (settings.gpuMemoryBudget), each piece written into gl's mesh buffers and then
    // drawn by drawPiece(triangles) before the next one replaces it. False when the source has
    // no such path (the CPU: the renderer extracts bricks itself).
    using PieceDrawer = std::function<void(std::size_t triangles)>;
    virtual bool extractPiecesInto(SilhouetteGlRenderer& /*gl*/,
                                   const SilhouetteSettings& /*settings*/,
                                   const PieceDrawer& /*drawPiece*/) {
        return false;
    }
    // Forget the bound volume (SilhouetteRenderer::releaseVolume).
    virtual void releaseVolume() {}
};

// The CUDA source, or null where this build has no CUDA-GL interop.
std::unique_ptr<GlMeshSource> makeCudaGlMeshSource();

} // namespace lw::render
