#pragma once

// The shaded iso-surface panel without OpenGL: method 3's rasterizer keeps the nearest triangle
// per pixel, and each pixel is lit Blinn-Phong with the perspective-correctly interpolated
// vertex normal and a headlight (light at the eye). The GL renderer does the same on GPUs; this
// is the fallback where no GL context exists and the reference it is compared with.

#include "lw/core/image.h"
#include "lw/render/camera.h"
#include "lw/render/iso_surface.h"
#include "lw/render/silhouette_gl_renderer.h"

#include <optional>
#include <vector>

namespace lw::render {

struct SurfaceShading {
    core::Rgba8 background{255, 255, 255, 255};
    core::Rgba8 surface{200, 200, 200, 255}; // light grey
    double ambient = 0.15;
    double diffuse = 0.75;
    double specular = 0.25;
    double shininess = 32.0;
    unsigned threads = 0; // 0 = all cores
    // Unit direction toward the light in patient coordinates; zero = a headlight (the default).
    // With a light, shading is Blinn-Phong as in the GL panel's surface shader.
    glm::dvec3 lightDirection{0.0};
    // Colour of inner faces (seen through a surface cut open by the volume border); by default
    // the surface colour, lit two-sided.
    std::optional<core::Rgba8> backSurface;
};

// The shading of the GL iso panel (SilhouetteGlRenderer's surface pass with `options`) for this
// camera: same light, colours and material, so a panel drawn on the CPU looks like the GL one.
SurfaceShading glPanelShading(const Camera& camera, const SilhouetteGlOptions& options);

// Lit mesh on the camera's viewport, top row first. Back faces (seen through a surface cut open
// by the volume's border) are lit two-sided.
// `depth` (optional) receives each pixel's depth as a GL depth buffer holds it, top row first:
// (NDC depth + 1) / 2, 1 where no surface is (picking with Camera::unproject).
core::ImageRgba8 shadeSurfaceCpu(const Mesh& mesh, const Camera& camera,
                                 const SurfaceShading& shading = {},
                                 std::vector<float>* depth = nullptr);

} // namespace lw::render
