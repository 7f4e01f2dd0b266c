#pragma once

// Camera -> the plain view description the CPU kernels take (kernels do not know render types).

#include "lw/kernels/cpu/zbuffer_rasterizer_cpu.h"
#include "lw/render/camera.h"

namespace lw::render {

inline kernels::cpu::ViewTransform toViewTransform(const Camera& camera) {
    kernels::cpu::ViewTransform view;
    view.viewProjection = camera.viewProjectionMatrix();
    view.width = camera.width();
    view.height = camera.height();
    view.orthographic = camera.isOrthographic();
    view.eye = camera.eye();
    view.toViewer = -camera.forward();
    return view;
}

} // namespace lw::render
