#include "settings/review_layout.h"

#include <QSettings>
#include <QString>

namespace lw::gui {
namespace {

// Stored by name, so a reordered enum keeps what users chose.
constexpr std::pair<ReviewLayout, const char*> kLayoutNames[] = {
    {ReviewLayout::Surfaces, "surfaces"},
    {ReviewLayout::SurfacesAndSlices, "surfaces+slices"},
    {ReviewLayout::SilhouetteAndSlice, "silhouette+slice"}};

} // namespace

ReviewLayoutChoice ReviewLayoutChoice::load(QSettings& settings) {
    ReviewLayoutChoice choice;
    const QString layout = settings.value("review/layout").toString();
    for (const auto& [value, name] : kLayoutNames)
        if (layout == QLatin1String(name))
            choice.layout = value;
    const QString plane = settings.value("review/largeSlice").toString();
    choice.largeSlice =
        volume::parseSliceOrientation(plane.toStdString()).value_or(choice.largeSlice);
    return choice;
}

void ReviewLayoutChoice::save(QSettings& settings) const {
    for (const auto& [value, name] : kLayoutNames)
        if (value == layout)
            settings.setValue("review/layout", QString::fromLatin1(name));
    const std::string_view plane = volume::sliceOrientationName(largeSlice);
    settings.setValue("review/largeSlice",
                      QString::fromLatin1(plane.data(), qsizetype(plane.size())));
}

} // namespace lw::gui
