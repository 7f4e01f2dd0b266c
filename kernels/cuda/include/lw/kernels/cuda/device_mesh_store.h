#pragma once

// Device copies of meshes kept from one frame to the next. Method 3's streamed (L) frames keep
// each slab's mesh here while the memory budget allows, so that a new view of the same surface
// draws the kept slabs and streams only the others.

#include "lw/kernels/cuda/cuda_status.h"
#include "lw/kernels/cuda/marching_cubes_cuda.h"

#include <cstddef>
#include <memory>

namespace lw::kernels::cuda {

class DeviceMeshStore {
public:
    DeviceMeshStore();
    ~DeviceMeshStore();
    DeviceMeshStore(const DeviceMeshStore&) = delete;
    DeviceMeshStore& operator=(const DeviceMeshStore&) = delete;

    // The device bytes a copy of `mesh` takes (positions, normals and indices in one allocation).
    static std::size_t bytesOf(const DeviceMeshView& mesh);

    // Copies `mesh` (device memory, complete: its producer has synchronised) into an allocation of
    // its own and returns when the copy is done. Out of memory leaves the store as it was.
    CudaStatus keep(const DeviceMeshView& mesh);

    std::size_t count() const;
    const DeviceMeshView& mesh(std::size_t index) const;
    std::size_t deviceBytes() const;
    void clear(); // frees every copy

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace lw::kernels::cuda
