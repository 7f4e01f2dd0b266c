#include "review/slice_views.h"

#include "review/slice_sampler.h"
#include "review/slice_view.h"

#include <QThreadPool>
#include <algorithm>

namespace lw::gui {
namespace {

constexpr volume::SliceOrientation kOrientations[] = {volume::SliceOrientation::Axial,
                                                      volume::SliceOrientation::Coronal,
                                                      volume::SliceOrientation::Sagittal};

// What a series opens with: soft tissue for CT; otherwise its whole value range.
WindowLevel initialWindow(const volume::Volume& volume, bool hounsfield) {
    if (hounsfield)
        return windowPreset(WindowPreset::SoftTissue);
    const volume::ValueRange range = volume.realRange();
    return {std::max(1.0, range.max - range.min), 0.5 * (range.max + range.min)};
}

} // namespace

QString valueUnit(const QString& modality, bool phantom) {
    if (modality == QLatin1String("CT") || (modality.isEmpty() && phantom))
        return QStringLiteral("HU");
    return modality.isEmpty() ? QObject::tr("stored units")
                              : QObject::tr("%1 stored units").arg(modality);
}

SliceViews::SliceViews(std::shared_ptr<const volume::Volume> volume, QString unit, QObject* parent)
    : QObject(parent), m_volume(std::move(volume)), m_unit(std::move(unit)),
      m_pool(std::make_unique<QThreadPool>()) {
    // Two threads: the wheel's view and one more; the render worker has its own thread.
    m_pool->setMaxThreadCount(2);
    m_window = initialWindow(*m_volume, isHounsfield());
    for (volume::SliceOrientation orientation : kOrientations) {
        Slot& made = slot(orientation);
        const volume::SliceGeometry geometry = volume::sliceGeometry(*m_volume, orientation);
        made.view = new SliceView(geometry);
        made.sampler = new SliceSampler(m_volume, geometry, *m_pool, this);
        made.view->setWindowLevel(m_window);
        made.view->setValueReader([this](glm::dvec3 patient) { return valueText(patient); });
        connect(made.sampler, &SliceSampler::ready, made.view, &SliceView::setSlice);
        connect(made.view, &SliceView::positionChanged, this, [this, &made] { request(made); });
        connect(made.view, &SliceView::windowLevelDragged, this, &SliceViews::setWindowLevel);
        connect(made.view, &SliceView::linkRequested, this, &SliceViews::linkRequested);
    }
}

SliceViews::~SliceViews() {
    // Results post back to the samplers: none may run once they are gone.
    m_pool->waitForDone();
}

SliceViews::Slot& SliceViews::slot(volume::SliceOrientation orientation) {
    return m_slots[std::size_t(orientation)];
}

const SliceViews::Slot& SliceViews::slot(volume::SliceOrientation orientation) const {
    return m_slots[std::size_t(orientation)];
}

SliceView& SliceViews::view(volume::SliceOrientation orientation) {
    return *slot(orientation).view;
}

void SliceViews::setActive(volume::SliceOrientation orientation, bool active) {
    Slot& changed = slot(orientation);
    const bool wasActive = changed.active;
    changed.active = active;
    if (active && !wasActive)
        request(changed);
}

bool SliceViews::isActive(volume::SliceOrientation orientation) const {
    return slot(orientation).active;
}

bool SliceViews::isBusy() const {
    return std::any_of(m_slots.begin(), m_slots.end(),
                       [](const Slot& s) { return s.sampler->isBusy(); });
}

void SliceViews::request(Slot& slot) {
    if (!slot.active)
        return;
    const SliceResult* shown = slot.view->slice();
    if (shown && shown->image && shown->image->position == slot.view->position() &&
        shown->iso == m_iso && shown->contourOfDrawnCopy == slot.sampler->contoursDrawnCopy(m_iso))
        return; // on screen already
    slot.sampler->request(slot.view->position(), m_iso);
}

void SliceViews::setIso(double iso) {
    if (iso == m_iso)
        return;
    m_iso = iso;
    for (Slot& each : m_slots) {
        // The copy of the old iso-value goes: the worker drops it for the new one, and two
        // copies of a large series should not live at once.
        if (!each.sampler->contoursDrawnCopy(iso))
            each.sampler->setDrawnSurface(nullptr, iso);
        request(each);
    }
}

void SliceViews::setDrawnSurface(std::shared_ptr<const volume::Volume> copy, double iso) {
    for (Slot& each : m_slots) {
        each.sampler->setDrawnSurface(copy, iso);
        if (iso == m_iso)
            request(each);
    }
}

void SliceViews::setContourColour(const QColor& colour) {
    for (Slot& each : m_slots)
        each.view->setContourColour(colour);
}

void SliceViews::setWindowLevel(WindowLevel window) {
    m_window = window;
    for (Slot& each : m_slots)
        each.view->setWindowLevel(window);
    emit windowLevelChanged(window);
}

void SliceViews::applyPreset(WindowPreset preset) {
    setWindowLevel(windowPreset(preset));
}

void SliceViews::linkTo(glm::dvec3 patient) {
    m_linked = patient;
    for (Slot& each : m_slots) {
        each.view->setMarker(patient);
        each.view->setPosition(each.view->geometry().positionOf(patient));
    }
}

QString SliceViews::valueText(glm::dvec3 patient) const {
    const std::optional<double> value = volume::sampleAt(*m_volume, patient);
    if (!value)
        return {};
    return tr("%1 %2 · %3")
        .arg(*value, 0, 'f', isHounsfield() ? 0 : 1)
        .arg(m_unit, patientPointText(patient));
}

} // namespace lw::gui
