#include "lw/render/silhouette_methods.h"

#include "lw/core/error.h"

#include <array>
#include <string>

// The labels are translated by the workstation: lupdate reads this file and takes
// LW_TRANSLATE_NOOP for QT_TRANSLATE_NOOP (translations/CMakeLists.txt). Here it is the text.
#define LW_TRANSLATE_NOOP(context, text) text

namespace lw::render {
namespace {

constexpr std::array<SilhouetteMethodInfo, 3> kMethods = {{
    {SilhouetteMethod::GeometryShader, 1, "1", "marching cubes + geometry-shader silhouette",
     LW_TRANSLATE_NOOP("lw::render::SilhouetteMethod",
                       "Method 1: marching cubes + geometry shader"),
     /*keepsMesh*/ true, /*drawsToTexture*/ false, /*hasCuda*/ true, /*hasChunked*/ true,
     /*needsOpenGl*/ true},
    {SilhouetteMethod::RayCastVisibility, 2, "2", "silhouette with ray-cast visibility",
     LW_TRANSLATE_NOOP("lw::render::SilhouetteMethod",
                       "Method 2: silhouette only + ray-cast visibility"),
     /*keepsMesh*/ false, /*drawsToTexture*/ false, /*hasCuda*/ true, /*hasChunked*/ true,
     /*needsOpenGl*/ false},
    {SilhouetteMethod::ZBuffer, 3, "3", "z-buffer silhouette",
     LW_TRANSLATE_NOOP("lw::render::SilhouetteMethod", "Method 3: own z-buffer rasterizer"),
     /*keepsMesh*/ true, /*drawsToTexture*/ true, /*hasCuda*/ true, /*hasChunked*/ true,
     /*needsOpenGl*/ false},
}};

} // namespace

std::span<const SilhouetteMethodInfo> silhouetteMethods() {
    return kMethods;
}

const SilhouetteMethodInfo& silhouetteMethodInfo(SilhouetteMethod method) {
    for (const SilhouetteMethodInfo& info : kMethods)
        if (info.method == method)
            return info;
    throw core::Error("silhouette method", std::to_string(int(method)) + " is no method");
}

const SilhouetteMethodInfo* findSilhouetteMethod(std::string_view key) {
    for (const SilhouetteMethodInfo& info : kMethods)
        if (info.key == key)
            return &info;
    return nullptr;
}

std::string silhouetteMethodKeys() {
    std::string keys;
    for (std::size_t i = 0; i < kMethods.size(); ++i) {
        if (i > 0)
            keys += i + 1 == kMethods.size() ? " or " : ", ";
        keys += kMethods[i].key;
    }
    return keys;
}

} // namespace lw::render
