#pragma once

// The renderer tests run over every back-end present: the CPU everywhere, CUDA where a device is
// (the GPU machine), so the CPU fixtures are the CUDA fixtures. Instantiate a TEST_P suite with
//   INSTANTIATE_TEST_SUITE_P(Backends, Suite, testing::ValuesIn(lw::test::backendsUnderTest()),
//                            lw::test::backendTestName);

#include "lw/render/renderer_factory.h"

#include <gtest/gtest.h>
#include <string>
#include <vector>

namespace lw::test {

inline std::vector<render::Backend> backendsUnderTest() {
    std::vector<render::Backend> backends{render::Backend::Cpu};
    if (render::cudaAvailability().available)
        backends.push_back(render::Backend::Cuda);
    return backends;
}

inline std::string backendTestName(const testing::TestParamInfo<render::Backend>& info) {
    return std::string(render::backendName(info.param));
}

} // namespace lw::test
