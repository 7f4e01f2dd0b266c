// makeCudaGlMeshSource() where lw_render is built without the CUDA back-end (with it,
// cuda/cuda_gl_mesh_source.cpp defines it).
#include "gl_mesh_source.h"

#if !LINEWORK_CUDA
namespace lw::render {
std::unique_ptr<GlMeshSource> makeCudaGlMeshSource() {
    return nullptr;
}
} // namespace lw::render
#endif
