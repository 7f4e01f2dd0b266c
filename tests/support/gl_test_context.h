#pragma once

// The headless OpenGL context of a GL test binary (one linked with lw_gtest_main_gl). That main
// creates it before RUN_ALL_TESTS, exits with the SKIP code when it cannot, and releases it after,
// so inside a test the context always exists. It is current on the main thread unless a test made
// another context current (call makeCurrent() again then).

#include "lw/render/gl_context.h"

namespace lw::test {

lw::render::EglHeadlessContext& glContext();

} // namespace lw::test
