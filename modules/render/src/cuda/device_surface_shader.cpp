#include "device_surface_shader.h"

#include "../view_transform.h"

namespace lw::render {
namespace {

glm::dvec3 colourOf(core::Rgba8 c) {
    return {double(c.r), double(c.g), double(c.b)};
}

kernels::cuda::SurfaceLighting lightingOf(const SurfaceShading& shading) {
    kernels::cuda::SurfaceLighting lighting;
    lighting.background = colourOf(shading.background);
    lighting.front = colourOf(shading.surface);
    lighting.back = colourOf(shading.backSurface.value_or(shading.surface));
    lighting.ambient = shading.ambient;
    lighting.diffuse = shading.diffuse;
    lighting.specular = shading.specular;
    lighting.shininess = shading.shininess;
    lighting.lightDirection = shading.lightDirection;
    return lighting;
}

} // namespace

kernels::cuda::CudaStatus DeviceSurfaceShader::shade(const Camera& camera,
                                                     const SurfaceShading& shading,
                                                     const kernels::cuda::DeviceMeshView& mesh,
                                                     const Mesh* cap, core::ImageRgba8& image,
                                                     std::vector<float>* depth, Shaded& shaded) {
    LW_RETURN_IF_FAILED(m_shading.begin(toViewTransform(camera)));
    LW_RETURN_IF_FAILED(m_shading.draw(mesh));
    shaded.triangles = mesh.triangleCount;
    if (cap && !cap->isEmpty()) {
        if (m_capOnDevice != cap) {
            m_capOnDevice = nullptr;
            LW_RETURN_IF_FAILED(m_shading.keepHostMesh(*cap));
            m_capOnDevice = cap;
        }
        LW_RETURN_IF_FAILED(m_shading.drawKeptHostMesh());
        shaded.triangles += cap->triangleCount();
    }
    image = core::ImageRgba8(camera.width(), camera.height(), shading.background);
    if (depth)
        depth->assign(std::size_t(camera.width()) * std::size_t(camera.height()), 1.0f);
    kernels::cuda::SurfaceShadingTimes times;
    LW_RETURN_IF_FAILED(m_shading.shade(lightingOf(shading), image.bytes(),
                                        depth ? depth->data() : nullptr, times));
    shaded.rasterMs = times.rasterMs;
    shaded.shadeMs = times.shadeMs;
    return kernels::cuda::CudaStatus::success();
}

} // namespace lw::render
