#pragma once

// The shaded iso-surface panel without OpenGL: method 3's rasterizer keeps the nearest triangle
// per pixel, and each pixel is lit Blinn-Phong with the perspective-correctly interpolated
// vertex normal and a headlight (light at the eye). The GL renderer does the same on GPUs; this
// is the fallback where no GL context exists and the reference it is compared with.

#include "lw/core/image.h"
#include "lw/render/camera.h"
#include "lw/render/iso_surface.h"

namespace lw::render {

struct SurfaceShading {
    core::Rgba8 background{255, 255, 255, 255};
    core::Rgba8 surface{200, 200, 200, 255}; // light grey
    double ambient = 0.15;
    double diffuse = 0.75;
    double specular = 0.25;
    double shininess = 32.0;
    unsigned threads = 0; // 0 = all cores
};

// Lit mesh on the camera's viewport, top row first. Back faces (seen through a surface cut open
// by the volume's border) are lit two-sided.
core::ImageRgba8 shadeSurfaceCpu(const Mesh& mesh, const Camera& camera,
                                 const SurfaceShading& shading = {});

} // namespace lw::render
