#pragma once

// The silhouette methods, one descriptor each: what the CLI, the workstation, the settings, the
// benchmarks and the reports need to know about a method, kept in one place. A new method is a
// new SilhouetteMethod value, its row in silhouette_methods.cpp, its renderer (and kernels) and
// the translations of its label; the callers iterate silhouetteMethods() and ask the descriptor
// or the renderer instance, never a method number or a back-end's name.

#include "lw/render/silhouette_renderer.h"

#include <span>
#include <string_view>

namespace lw::render {

struct SilhouetteMethodInfo {
    SilhouetteMethod method;
    int number;            // Morar et al.'s numbering, as the CLI and the reports print it
    std::string_view key;  // "1", "2", ...: --method, bench's --methods, the settings file
    std::string_view name; // what a report says the method is, in English
    // The settings page's label: English source text, translated by the workstation in the
    // context kSilhouetteMethodContext.
    std::string_view label;
    bool keepsMesh;      // its frames leave the iso-surface mesh on the host (surfaceMesh())
    bool drawsToTexture; // on CUDA, can draw its lines into a GL texture (drawsToFrameTargets())
    bool hasCuda;        // has CUDA kernels (Backend::Auto picks them where a device is present)
    bool hasChunked;     // has the chunked (L) variant, a brick schedule of the same code
    bool needsOpenGl;    // draws with OpenGL (a context is needed even for the CPU back-end)
};

inline constexpr const char* kSilhouetteMethodContext = "lw::render::SilhouetteMethod";

// Every method, in number order.
std::span<const SilhouetteMethodInfo> silhouetteMethods();
// The descriptor of `method`; throws core::Error for a value that is no method.
const SilhouetteMethodInfo& silhouetteMethodInfo(SilhouetteMethod method);
// The method whose key is `key`, or null.
const SilhouetteMethodInfo* findSilhouetteMethod(std::string_view key);
// The keys joined: "1, 2 or 3" (for messages).
std::string silhouetteMethodKeys();

} // namespace lw::render
