#pragma once

// Picks the implementation of a silhouette method for a requested back-end, so the CLI, the GUI
// and the benchmarks do not each repeat the choice: one interface per method
// (silhouette_renderer.h), its back-end chosen at run time.

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

// Whether this build has the CUDA back-end and this machine a device for it (probed once per
// process; no driver or no GPU is an answer, never a crash).
struct CudaAvailability {
    bool built = false;
    bool available = false;
    std::string deviceName;
    std::string reason; // why not available
};
CudaAvailability cudaAvailability();

// The back-end a request for `method` runs on. Cpu stays Cpu. Auto is CUDA when the build has it,
// a device is present and the method has CUDA kernels (methods 2 and 3 today), else CPU; the note
// says which and why ("auto: CUDA on NVIDIA H100 80GB HBM3", "auto: no CUDA device ..., using
// CPU"). Cuda throws core::Error("--backend cuda", reason) when it cannot be honoured. Commands
// call it up front to fail before any work. Without a method: as for method 3.
Backend resolveBackend(Backend requested, SilhouetteMethod method,
                       std::string* backendNote = nullptr);
Backend resolveBackend(Backend requested, std::string* backendNote = nullptr);

// Method 1 -> the GL adapter (GeometryShaderSilhouetteRenderer on a headless EGL context),
// method 2 -> RayCastSilhouetteRenderer, method 3 -> ZBufferSilhouetteRenderer.
// The back-end as resolveBackend() chooses it; Backend::Auto's note also goes to the lw.render log.
// Throws core::Error("method 1", "no OpenGL context: <reason>") when GL is not built or EGL fails.
std::unique_ptr<SilhouetteRenderer> createSilhouetteRenderer(SilhouetteMethod method,
                                                             Backend requested = Backend::Auto,
                                                             std::string* backendNote = nullptr);

} // namespace lw::render
