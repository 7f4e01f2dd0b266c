#pragma once

// Assertions the volume reader tests share.

#include "lw/core/error.h"

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include <string>

namespace lw::volume::testfiles {

inline void expectNear(glm::dvec3 a, glm::dvec3 b, double tolerance) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

// Runs `read` and requires a core::Error whose text contains `needle`.
template <typename F> void expectError(F&& read, const std::string& needle) {
    try {
        read();
        FAIL() << "expected an error containing '" << needle << "'";
    } catch (const core::Error& e) {
        EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
}

} // namespace lw::volume::testfiles
