#include "settings/review_settings.h"

#include "lw/render/iso_surface.h"
#include "lw/render/silhouette_methods.h"

#include <QCoreApplication>
#include <QObject>
#include <QSettings>
#include <algorithm>

namespace lw::gui {
namespace {

// QSettings keys; one group so the review's settings are easy to find and reset.
constexpr const char* kGroup = "review";

int clampInt(const QVariant& value, int low, int high, int fallback) {
    bool ok = false;
    const int number = value.toInt(&ok);
    return ok ? std::clamp(number, low, high) : fallback;
}

QColor colourOr(const QVariant& value, QColor fallback) {
    const QColor colour(value.toString());
    return colour.isValid() ? colour : fallback;
}

QList<IsoPreset> readPresets(QSettings& settings) {
    QList<IsoPreset> presets;
    const int count = settings.beginReadArray("presets");
    for (int i = 0; i < count; ++i) {
        settings.setArrayIndex(i);
        bool ok = false;
        const double hu = settings.value("hu").toDouble(&ok);
        const QString name = settings.value("name").toString().trimmed();
        if (ok && !name.isEmpty())
            presets.append({name, hu});
    }
    settings.endArray();
    return presets.isEmpty() ? ReviewSettings::defaultPresets() : presets;
}

} // namespace

QList<IsoPreset> ReviewSettings::defaultPresets() {
    // Bone at 400 HU keeps the skull and spine closed on typical head and body CT; skin at
    // -500 HU sits between air (-1000) and soft tissue (~0-60).
    // The names are the interface language's; once stored they are the user's own.
    return {{QObject::tr("Bone"), 400.0}, {QObject::tr("Skin"), -500.0}};
}

ReviewSettings ReviewSettings::load(QSettings& settings) {
    ReviewSettings s;
    settings.beginGroup(kGroup);
    // A key no method has (an older or newer build's) keeps the default.
    if (const render::SilhouetteMethodInfo* info =
            render::findSilhouetteMethod(settings.value("method").toString().toStdString()))
        s.method = info->method;
    s.chunking = Chunking(clampInt(settings.value("chunking"), 0, 2, int(s.chunking)));
    s.fixedBrickCells = clampInt(settings.value("brickCells"), 8, 1024, s.fixedBrickCells);
    s.memoryBudgetMiB = clampInt(settings.value("memoryBudgetMiB"), 64, 1 << 20, s.memoryBudgetMiB);
    s.gpuMemoryBudgetMiB =
        clampInt(settings.value("gpuMemoryBudgetMiB"), 0, 1 << 20, s.gpuMemoryBudgetMiB);
    s.mode = settings.value("mode", "a").toString() == "b" ? render::ExtractionMode::EveryFrameB
                                                           : render::ExtractionMode::CachedA;
    s.visibility = settings.value("visibility", s.visibility).toBool();
    s.testAlongSegment = settings.value("alongSegment", s.testAlongSegment).toBool();
    s.minStrokePixels = clampInt(settings.value("minStrokePixels"), 0, 1000, s.minStrokePixels);
    s.closeAtBorder = settings.value("closeAtBorder", s.closeAtBorder).toBool();
    s.gradientStencil =
        render::parseGradientStencil(settings.value("gradient").toString().toStdString())
            .value_or(s.gradientStencil);
    s.oversampling =
        render::parseOversampling(settings.value("oversample").toString().toStdString())
            .value_or(s.oversampling);
    s.thickSlices = render::parseThickSlices(settings.value("thickSlices").toString().toStdString())
                        .value_or(s.thickSlices);
    s.suggestiveContours = settings.value("suggestiveContours", s.suggestiveContours).toBool();
    s.lineWidth = std::clamp(settings.value("lineWidth", s.lineWidth).toDouble(), 1.0, 8.0);
    s.lineColour = colourOr(settings.value("lineColour"), s.lineColour);
    s.hiddenLines = settings.value("hiddenLines", s.hiddenLines).toBool();
    s.background = colourOr(settings.value("background"), s.background);
    s.contourColour = colourOr(settings.value("contourColour"), s.contourColour);
    s.silhouetteOnIso = settings.value("silhouetteOnIso", s.silhouetteOnIso).toBool();
    s.projection = settings.value("projection").toString() == "ortho"
                       ? render::Projection::Orthographic
                       : render::Projection::Perspective;
    const QString backend = settings.value("backend", "auto").toString();
    s.backend = backend == "cpu"    ? render::Backend::Cpu
                : backend == "cuda" ? render::Backend::Cuda
                                    : render::Backend::Auto;
    s.panelGl = PanelGl(clampInt(settings.value("panelGl"), 0, 2, int(s.panelGl)));
    s.cudaShadesIsoPanel = settings.value("cudaShadesIsoPanel", s.cudaShadesIsoPanel).toBool();
    s.presets = readPresets(settings);
    settings.endGroup();
    return s;
}

void ReviewSettings::save(QSettings& settings) const {
    settings.beginGroup(kGroup);
    settings.setValue(
        "method", QString::fromUtf8(render::silhouetteMethodInfo(method).key.data(),
                                    qsizetype(render::silhouetteMethodInfo(method).key.size())));
    settings.setValue("chunking", int(chunking));
    settings.setValue("brickCells", fixedBrickCells);
    settings.setValue("memoryBudgetMiB", memoryBudgetMiB);
    settings.setValue("gpuMemoryBudgetMiB", gpuMemoryBudgetMiB);
    settings.setValue("mode", mode == render::ExtractionMode::EveryFrameB ? "b" : "a");
    settings.setValue("visibility", visibility);
    settings.setValue("alongSegment", testAlongSegment);
    settings.setValue("minStrokePixels", minStrokePixels);
    settings.setValue("closeAtBorder", closeAtBorder);
    settings.setValue("gradient",
                      QString::fromUtf8(render::gradientStencilName(gradientStencil).data()));
    settings.setValue("oversample",
                      QString::fromUtf8(render::oversamplingName(oversampling).data()));
    settings.setValue("thickSlices",
                      QString::fromUtf8(render::thickSlicesName(thickSlices).data()));
    settings.setValue("suggestiveContours", suggestiveContours);
    settings.setValue("lineWidth", lineWidth);
    settings.setValue("lineColour", lineColour.name());
    settings.setValue("hiddenLines", hiddenLines);
    settings.setValue("background", background.name());
    settings.setValue("contourColour", contourColour.name());
    settings.setValue("silhouetteOnIso", silhouetteOnIso);
    settings.setValue("projection",
                      projection == render::Projection::Orthographic ? "ortho" : "perspective");
    settings.setValue("backend", QString::fromUtf8(render::backendName(backend).data()));
    settings.setValue("panelGl", int(panelGl));
    settings.setValue("cudaShadesIsoPanel", cudaShadesIsoPanel);
    settings.beginWriteArray("presets", int(presets.size()));
    for (int i = 0; i < presets.size(); ++i) {
        settings.setArrayIndex(i);
        settings.setValue("name", presets[i].name);
        settings.setValue("hu", presets[i].hu);
    }
    settings.endArray();
    settings.endGroup();
}

int ReviewSettings::brickCellsFor(glm::ivec3 dims, std::size_t bytes) const {
    switch (chunking) {
    case Chunking::Off:
        return 0;
    case Chunking::Fixed:
        return fixedBrickCells;
    case Chunking::Auto:
        break;
    }
    const double wholePathBytes = 2.0 * double(bytes);
    return wholePathBytes > double(memoryBudgetMiB) * 1024.0 * 1024.0 ? render::autoBrickCells(dims)
                                                                      : 0;
}

QString methodName(render::SilhouetteMethod method) {
    const std::string label(render::silhouetteMethodInfo(method).label);
    return QCoreApplication::translate(render::kSilhouetteMethodContext, label.c_str());
}

render::SilhouetteSettings ReviewSettings::silhouetteSettings(int brickCells, double iso) const {
    render::SilhouetteSettings settings;
    settings.isoReal = iso;
    settings.brickCells = brickCells;
    settings.mode = mode;
    settings.visibility = visibility;
    settings.testAlongSegment = testAlongSegment;
    settings.minStrokePixels = minStrokePixels;
    settings.closeAtBorder = closeAtBorder;
    settings.gradientStencil = gradientStencil;
    settings.gpuMemoryBudget = std::size_t(gpuMemoryBudgetMiB) << 20;
    return settings;
}

} // namespace lw::gui
