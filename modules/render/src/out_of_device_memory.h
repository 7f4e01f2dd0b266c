#pragma once

#include <stdexcept>

namespace lw::render {

// A back-end ran out of device memory (or over its budget) in the middle of a frame: the
// renderer repeats the frame the next way down (a leaner way on the same device, then the CPU).
// Thrown by the kernel sets (zbuffer_kernel_set.h, raycast_kernel_set.h), caught by the renderers.
struct OutOfDeviceMemory : std::runtime_error {
    using std::runtime_error::runtime_error;
};

} // namespace lw::render
