#pragma once

// Method 3 on the GPU: the paper's own z-buffer rasterizer as CUDA kernels over a device mesh.
//   project     per vertex: fixed-point screen position, depth key, Burns' d
//   silhouette  per triangle: Burns' segment where d changes sign, drawn straight into zbuffer2
//               with atomicMax on the key bits (no segment list is stored)
//   depth       per triangle: covered pixel centres into zbuffer1, atomicMax (back faces culled
//               when the surface is closed)
//   resolve     per pixel: the colour pass, into a byte mask copied to the host, or straight
//               into a GL texture through CUDA-GL interop (the GUI's silhouette panel)
//   prune       short strokes cleared from the mask on the device (stroke_pruning.h), before
//               either
// Every rule comes from lw/kernels/zbuffer_rules.h, shared with the CPU rasterizer, so the mask
// equals the CPU's. Public header: no CUDA types.

#include "lw/kernels/cuda/cuda_status.h"
#include "lw/kernels/cuda/marching_cubes_cuda.h"
#include "lw/kernels/triangle_mesh.h"
#include "lw/kernels/zbuffer_rules.h"

#include <cstddef>
#include <cstdint>
#include <memory>

namespace lw::kernels::cuda {

class GlTextureInterop;

struct ZBufferCudaFrame {
    std::size_t segments = 0;
    // CUDA events. drawMs: the silhouette and, with visibility on, the surface's depth, drawn in
    // one pass over the triangles.
    double projectMs = 0, drawMs = 0, resolveMs = 0;
};

struct ZBufferCudaSettings {
    float epsilon = 0.0f;       // depth tolerance of the colour pass (keys)
    bool visibility = true;     // false: every segment pixel is drawn
    bool cullBackFaces = false; // only exact for a closed surface
    // Strokes of fewer pixels (joined across gaps of strokeGapPixels) cleared on the device after
    // the colour pass (stroke_pruning.h); 0 or 1: none.
    int minStrokePixels = 0;
    int strokeGapPixels = 0;
};

class ZBufferCuda {
public:
    ZBufferCuda();
    ~ZBufferCuda();
    ZBufferCuda(const ZBufferCuda&) = delete;
    ZBufferCuda& operator=(const ZBufferCuda&) = delete;

    // Clears both buffers for a view (call once per frame before drawing).
    CudaStatus begin(const ViewTransform& view);
    // Draws a mesh's silhouette segments into zbuffer2 and, with visibility, its triangles into
    // zbuffer1. Called once per frame (S) or once per brick (L): both buffers keep maxima. The
    // draw is queued on the device and may still read `mesh` after the call: a caller that
    // reuses the mesh's memory calls waitForDraws first. Its times reach the frame passed to the
    // next draw, waitForDraws or the resolve.
    CudaStatus draw(const DeviceMeshView& mesh, const ZBufferCudaSettings& settings,
                    ZBufferCudaFrame& frame);
    // Blocks until every queued draw has finished, and adds their times to `frame`.
    CudaStatus waitForDraws(ZBufferCudaFrame& frame);
    // The same for a mesh in host memory (the border cap: small), copied to the device first.
    CudaStatus drawHost(const TriangleMesh& mesh, const ZBufferCudaSettings& settings,
                        ZBufferCudaFrame& frame);
    // drawHost in two steps, for a host mesh drawn in many frames (the cap of a kept surface: mode
    // a turns the camera only): keepHostMesh copies it to the device, drawKeptHostMesh draws the
    // copy, until the next keepHostMesh or drawHost replaces it.
    CudaStatus keepHostMesh(const TriangleMesh& mesh);
    CudaStatus drawKeptHostMesh(const ZBufferCudaSettings& settings, ZBufferCudaFrame& frame);
    // The colour pass into `hostMask` (width * height bytes, 1 = silhouette).
    CudaStatus resolve(const ZBufferCudaSettings& settings, std::uint8_t* hostMask,
                       ZBufferCudaFrame& frame);
    // The colour pass into the GL texture `target` (attached at the view's size; its GL context
    // current): mapped on this renderer's stream, written by the compose kernel, unmapped. The
    // texels equal resolve()'s mask bytes; nothing goes through host memory.
    CudaStatus resolveInto(const ZBufferCudaSettings& settings, const GlTextureInterop& target,
                           ZBufferCudaFrame& frame);

    std::size_t deviceBytes() const; // buffers held now
    void release();                  // frees every buffer (after running out of memory)

    struct Impl;

private:
    CudaStatus finishResolve(ZBufferCudaFrame& frame); // timing, segment count, synchronise

    std::unique_ptr<Impl> m_impl;
};

} // namespace lw::kernels::cuda
