#pragma once

// Picks the implementation of a silhouette method for a requested back-end, so the CLI, the GUI
// and the benchmarks do not each repeat the choice (DESIGN.md: one interface, chosen at run time).

#include "lw/render/silhouette_renderer.h"

#include <memory>
#include <string>
#include <string_view>

namespace lw::render {

enum class Backend { Cpu, Cuda, Auto };

// "1" | "2" | "3"; throws core::Error naming `option` (e.g. "--method") otherwise.
SilhouetteMethod parseSilhouetteMethod(std::string_view text, std::string_view option = "--method");
// "cpu" | "cuda" | "auto"; throws core::Error naming `option` otherwise.
Backend parseBackend(std::string_view text, std::string_view option = "--backend");
std::string_view backendName(Backend backend);

// The back-end a request runs on: Cpu for Cpu and for Auto (Auto says so in `backendNote`, if
// given; an explicit choice clears it). Throws core::Error for Cuda until the CUDA back-end
// exists. Commands call it up front to fail before any work.
Backend resolveBackend(Backend requested, std::string* backendNote = nullptr);

// Method 1 -> the GL adapter (GeometryShaderSilhouetteRenderer on a headless EGL context),
// method 2 -> RayCastSilhouetteRenderer, method 3 -> ZBufferSilhouetteRenderer.
// The back-end as resolveBackend() chooses it; Backend::Auto's note also goes to the lw.render log.
// Throws core::Error("method 1", "no OpenGL context: <reason>") when GL is not built or EGL fails.
std::unique_ptr<SilhouetteRenderer> createSilhouetteRenderer(SilhouetteMethod method,
                                                             Backend requested = Backend::Auto,
                                                             std::string* backendNote = nullptr);

} // namespace lw::render
