#include "lw/render/silhouette_renderer.h"

#include "lw/render/gl_frame_target.h"
#include "lw/render/iso_surface.h"

#include <chrono>

namespace lw::render {

FrameTargetUse frameTargetUse(glm::ivec2 targetSize, glm::ivec2 frameSize) {
    if (targetSize.x <= 0 || targetSize.y <= 0)
        return FrameTargetUse::NoTarget;
    if (targetSize != frameSize)
        return FrameTargetUse::SizeDiffers;
    return FrameTargetUse::Texture;
}

FrameTargetUse frameTargetUse(const SilhouetteSettings& settings, const Camera& camera) {
    const GlFrameTarget* target = settings.frameTarget;
    return frameTargetUse(target ? glm::ivec2(target->width(), target->height()) : glm::ivec2(0),
                          {camera.width(), camera.height()});
}

SilhouetteFrame SilhouetteRenderer::render(const Camera& camera,
                                           const SilhouetteSettings& settings) {
    SilhouetteFrame frame = renderFrame(camera, settings);
    if (settings.minStrokePixels > 1 && !frame.drewToTarget && !frame.strokesPruned) {
        const auto start = std::chrono::steady_clock::now();
        frame.lines.pruneStrokes(settings.minStrokePixels, kStrokeGapPixels);
        frame.times.drawMs +=
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
    }
    return frame;
}

Mesh surfaceOfFrame(const SilhouetteRenderer& renderer, const volume::Volume& volume,
                    const SilhouetteSettings& settings) {
    if (const Mesh* drawn = renderer.surfaceMesh())
        return *drawn;
    IsoSurfaceOptions options;
    options.threads = settings.threads;
    options.cancel = settings.cancel;
    options.closeAtBorder = settings.closeAtBorder;
    options.gradientStencil = settings.gradientStencil;
    return extractIsoSurface(volume, settings.isoReal, options);
}

} // namespace lw::render
