#pragma once

// The review's three slice panels (axial, coronal, sagittal) and what they share: the volume
// and its samplers, the iso-value their contours follow, the contour colour, one window/level
// (a preset or a right drag on any of them) and the linked cursor. ReviewWidget lays the views
// out; only the active ones (those the layout shows) are sampled.

#include "lw/volume/slice_plane.h"
#include "review/slice_image.h"

#include <QColor>
#include <QObject>
#include <QString>
#include <array>
#include <memory>
#include <optional>

class QThreadPool;

namespace lw::gui {

class SliceSampler;
class SliceView;

class SliceViews : public QObject {
    Q_OBJECT
public:
    // `unit`: what the values are in ("HU" for CT; otherwise the stored units, named).
    SliceViews(std::shared_ptr<const volume::Volume> volume, QString unit,
               QObject* parent = nullptr);
    ~SliceViews() override;

    SliceView& view(volume::SliceOrientation orientation);
    const QString& unit() const { return m_unit; }
    bool isHounsfield() const { return m_unit == QLatin1String("HU"); }
    // Sample the view (at its position and the iso-value) while it is shown; an inactive view
    // asks for nothing until it is activated again.
    void setActive(volume::SliceOrientation orientation, bool active);
    bool isActive(volume::SliceOrientation orientation) const;
    bool isBusy() const;

    void setIso(double iso);
    double iso() const { return m_iso; }
    // The resampled copy the 3D panels drew at `iso` (render::ReviewFrame::drawnVolume), null
    // where they draw the volume as loaded: the contours follow that surface (SliceSampler).
    void setDrawnSurface(std::shared_ptr<const volume::Volume> copy, double iso);
    void setContourColour(const QColor& colour);
    void setWindowLevel(WindowLevel window);
    WindowLevel windowLevel() const { return m_window; }
    void applyPreset(WindowPreset preset);

    // The linked cursor: every slice moved through `patient` and the point marked on each.
    void linkTo(glm::dvec3 patient);
    std::optional<glm::dvec3> linkedPoint() const { return m_linked; }

    // "412 HU · R 12.5 · A 3.0 · S 40.2 mm", or empty outside the volume.
    QString valueText(glm::dvec3 patient) const;

signals:
    void windowLevelChanged(lw::gui::WindowLevel window);
    // Shift+click on a slice: the review shows the point in 3D and calls linkTo.
    void linkRequested(glm::dvec3 patient);

private:
    struct Slot {
        SliceView* view = nullptr;
        SliceSampler* sampler = nullptr;
        bool active = false;
    };
    Slot& slot(volume::SliceOrientation orientation);
    const Slot& slot(volume::SliceOrientation orientation) const;
    void request(Slot& slot);

    std::shared_ptr<const volume::Volume> m_volume;
    QString m_unit;
    std::unique_ptr<QThreadPool> m_pool;
    std::array<Slot, 3> m_slots;
    double m_iso = 0.0;
    WindowLevel m_window;
    std::optional<glm::dvec3> m_linked;
};

// The unit of a series' values: "HU" for CT (DICOM modality CT, or the CT-like phantom),
// otherwise its stored units named after the modality.
QString valueUnit(const QString& modality, bool phantom);

} // namespace lw::gui
