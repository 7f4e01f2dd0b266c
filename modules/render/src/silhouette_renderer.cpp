#include "lw/render/silhouette_renderer.h"

#include <chrono>

namespace lw::render {

SilhouetteFrame SilhouetteRenderer::render(const Camera& camera,
                                           const SilhouetteSettings& settings) {
    SilhouetteFrame frame = renderFrame(camera, settings);
    if (settings.minStrokePixels > 1) {
        const auto start = std::chrono::steady_clock::now();
        frame.lines.removeComponentsSmallerThan(settings.minStrokePixels);
        frame.times.drawMs +=
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
    }
    return frame;
}

} // namespace lw::render
