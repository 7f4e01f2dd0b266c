#include "annotate/annotation_tool_controller.h"

#include "annotate/annotation_commands.h"
#include "annotate/annotation_document.h"
#include "review/review_panel.h"
#include "review/slice_view.h"

#include <QApplication>
#include <QEvent>
#include <QInputDialog>
#include <QMouseEvent>
#include <cmath>

namespace lw::gui {
namespace {

using annotation::AnnotationKind;

// Pixels of slack for grabbing an anchor or a line: about a fingertip of a mouse.
constexpr double kAnchorGrab = 7.0;
constexpr double kLineGrab = 5.0;

AnnotationKind kindOf(AnnotationTool tool) {
    switch (tool) {
    case AnnotationTool::Arrow:
        return AnnotationKind::Arrow;
    case AnnotationTool::Ruler:
        return AnnotationKind::Ruler;
    case AnnotationTool::Angle:
        return AnnotationKind::Angle;
    case AnnotationTool::None:
    case AnnotationTool::Label:
        break;
    }
    return AnnotationKind::Label;
}

// The slice a slice panel shows, for drawing and hit testing in its widget's pixels.
report::SlicePanelFrame sliceFrame(const SliceView& view) {
    report::SlicePanelFrame frame;
    frame.orientation = view.orientation();
    frame.positionMm = view.position();
    frame.spacingMm = std::abs(view.geometry().step);
    frame.toPixel = [&view](const glm::dvec3& patient) {
        const QPointF at = view.widgetPointOf(patient);
        return glm::dvec2(at.x(), at.y());
    };
    return frame;
}

// Where an annotation started on `panel` goes: the slice it shows, or nothing in 3D.
std::optional<annotation::SlicePlacement> placementOn(const QWidget& panel) {
    const auto* view = qobject_cast<const SliceView*>(&panel);
    if (!view)
        return std::nullopt;
    return annotation::SlicePlacement{view->orientation(), view->position(),
                                      std::abs(view->geometry().step)};
}

bool samePlane(const std::optional<annotation::SlicePlacement>& a,
               const std::optional<annotation::SlicePlacement>& b) {
    if (!a || !b)
        return !a && !b;
    return a->orientation == b->orientation && a->positionMm == b->positionMm;
}

std::optional<QString> askWithDialog(const QString& title, const QString& initial) {
    bool ok = false;
    // Over the window being annotated, not wherever the window manager puts a parentless dialog.
    const QString text = QInputDialog::getText(
        QApplication::activeWindow(), title, QObject::tr("Text:"), QLineEdit::Normal, initial, &ok);
    return ok ? std::optional<QString>(text) : std::nullopt;
}

} // namespace

AnnotationToolController::AnnotationToolController(AnnotationDocument& document, Picker pick,
                                                   QObject* parent)
    : QObject(parent), m_document(document), m_pick(std::move(pick)), m_prompt(askWithDialog) {
    // An edit from elsewhere (Ctrl+Z, Del) during a drag may remove what is dragged: the drag ends.
    connect(&m_document, &AnnotationDocument::changed, this, [this] {
        m_drag.reset();
        repaint();
    });
    connect(&m_document, &AnnotationDocument::selectionChanged, this,
            &AnnotationToolController::repaint);
}

void AnnotationToolController::attach(SliceView& view) {
    m_panels.emplace_back(&view);
    view.installEventFilter(this);
    // Widget pixels: the sizes are the 3D overlay's, which draws in device pixels at the ratio.
    view.setOverlayPainter([this, &view](QPainter& painter) {
        paintOverlay(painter, sliceFrame(view), scene(), 1.0);
    });
}

void AnnotationToolController::attach(ReviewPanel& panel) {
    m_panels.emplace_back(&panel);
    panel.installEventFilter(this);
    panel.setOverlayPainter([this, &panel](QPainter& painter, const render::Camera& camera) {
        paintOverlay(painter, camera, scene(), panel.devicePixelRatioF());
    });
}

void AnnotationToolController::setTool(AnnotationTool tool) {
    m_pending.clear();
    m_pendingSlice.reset();
    m_drag.reset();
    if (tool != m_tool) {
        m_tool = tool;
        emit toolChanged(tool);
    }
    announcePrompt();
    repaint();
}

void AnnotationToolController::cancel() {
    if (!m_pending.empty() || m_drag) {
        m_pending.clear();
        m_pendingSlice.reset();
        m_drag.reset();
        announcePrompt();
        repaint();
    } else if (m_tool != AnnotationTool::None) {
        setTool(AnnotationTool::None);
    } else {
        m_document.select(-1);
    }
}

void AnnotationToolController::deleteSelected() {
    if (m_document.selected() >= 0)
        m_document.remove(m_document.selected());
}

void AnnotationToolController::editSelectedText() {
    const int index = m_document.selected();
    if (index < 0)
        return;
    const annotation::Annotation& item = m_document.at(index);
    const std::optional<QString> text =
        m_prompt(tr("Text of the %1").arg(annotationKindLabel(item.kind)),
                 QString::fromStdString(item.text));
    if (!text)
        return;
    if (item.kind == AnnotationKind::Label && text->trimmed().isEmpty()) {
        emit refused(tr("A text label needs a text: delete it with Del instead"));
        return;
    }
    m_document.setText(index, text->trimmed().toStdString());
}

QString AnnotationToolController::prompt() const {
    const std::size_t placed = m_pending.size();
    switch (m_tool) {
    case AnnotationTool::None:
        return {};
    case AnnotationTool::Label:
        return tr("Text label: click the point on the surface to label");
    case AnnotationTool::Arrow:
        return placed == 0 ? tr("Arrow: click where its tail goes")
                           : tr("Arrow: click the point it shows (Esc cancels)");
    case AnnotationTool::Ruler:
        return placed == 0 ? tr("Ruler: click the first point on the surface")
                           : tr("Ruler: click the second point (Esc cancels)");
    case AnnotationTool::Angle:
        return placed == 0   ? tr("Angle: click the end of the first arm")
               : placed == 1 ? tr("Angle: click the vertex (Esc cancels)")
                             : tr("Angle: click the end of the second arm (Esc cancels)");
    }
    return {};
}

void AnnotationToolController::announcePrompt() {
    emit promptChanged(prompt());
}

void AnnotationToolController::repaint() {
    for (const QPointer<QWidget>& panel : m_panels) {
        if (auto* reviewPanel = qobject_cast<ReviewPanel*>(panel.data()))
            reviewPanel->repaintOverlay();
        else if (panel)
            panel->update();
    }
}

bool AnnotationToolController::eventFilter(QObject* watched, QEvent* event) {
    auto* panel = qobject_cast<QWidget*>(watched);
    if (!qobject_cast<ReviewPanel*>(panel) && !qobject_cast<SliceView*>(panel))
        return false;
    switch (event->type()) {
    case QEvent::MouseButtonPress:
        return mousePress(*panel, static_cast<QMouseEvent&>(*event));
    case QEvent::MouseMove:
        return mouseMove(*panel, static_cast<QMouseEvent&>(*event));
    case QEvent::MouseButtonRelease:
        return mouseRelease(*panel, static_cast<QMouseEvent&>(*event));
    case QEvent::MouseButtonDblClick:
        return doubleClick(*panel, static_cast<QMouseEvent&>(*event));
    case QEvent::Leave:
        m_pointerPanel.clear();
        repaint();
        return false;
    default:
        return false;
    }
}

bool AnnotationToolController::mousePress(QWidget& panel, QMouseEvent& event) {
    if (event.button() != Qt::LeftButton || event.modifiers() != Qt::NoModifier)
        return false; // zoom, pan and roll stay the camera's, whatever the tool
    const QPoint position = event.position().toPoint();
    panel.setFocus(); // the tools' keys (Esc, Del) act on the review clicked last
    // A release lost to a dialog (a label's text) must not keep swallowing later drags.
    m_swallowDrag = false;
    if (m_tool != AnnotationTool::None) {
        m_swallowDrag = true;
        placeAnchor(panel, position);
        return true;
    }
    const std::optional<AnnotationHit> hit = hitAt(panel, position);
    if (!hit) {
        m_document.select(-1);
        return false; // the camera turns
    }
    m_document.select(hit->annotation);
    m_swallowDrag = true;
    if (hit->anchor >= 0) {
        m_drag = Drag{hit->annotation, hit->anchor, position};
        m_pointerPanel = &panel;
        m_pointer = position;
    }
    return true;
}

bool AnnotationToolController::mouseMove(QWidget& panel, QMouseEvent& event) {
    m_pointerPanel = &panel;
    m_pointer = event.position().toPoint();
    if (m_drag || !m_pending.empty())
        repaint(); // the preview follows the mouse
    return m_swallowDrag && (event.buttons() & Qt::LeftButton);
}

bool AnnotationToolController::mouseRelease(QWidget& panel, QMouseEvent& event) {
    if (event.button() != Qt::LeftButton || !m_swallowDrag)
        return false;
    m_swallowDrag = false;
    if (m_drag)
        finishDrag(panel, event.position().toPoint());
    return true;
}

bool AnnotationToolController::doubleClick(QWidget& panel, QMouseEvent& event) {
    if (event.button() != Qt::LeftButton)
        return false;
    if (m_tool != AnnotationTool::None) // quick clicks while placing are clicks, not a double
        return mousePress(panel, event);
    const std::optional<AnnotationHit> hit = hitAt(panel, event.position().toPoint());
    if (!hit)
        return false;
    m_document.select(hit->annotation);
    m_swallowDrag = true;
    editSelectedText();
    return true;
}

void AnnotationToolController::placeAnchor(QWidget& panel, QPoint position) {
    const std::optional<annotation::SlicePlacement> placement = placementOn(panel);
    if (!m_pending.empty() && !samePlane(m_pendingSlice, placement)) {
        emit refused(tr("Click where the first point is: every point of one annotation lies on "
                        "the same slice, or in 3D (Esc cancels)"));
        return;
    }
    const std::optional<glm::dvec3> point = anchorAt(panel, position);
    if (!point) {
        emit refused(noAnchorReason(panel, false));
        return;
    }
    if (m_pending.empty())
        m_pendingSlice = placement;
    m_pending.push_back(*point);
    if (int(m_pending.size()) == annotation::anchorCount(kindOf(m_tool)))
        finishPlacement();
    announcePrompt();
    repaint();
}

void AnnotationToolController::finishPlacement() {
    annotation::Annotation made{kindOf(m_tool), std::move(m_pending), {}, m_pendingSlice};
    m_pending.clear();
    m_pendingSlice.reset();
    if (made.kind == AnnotationKind::Label) {
        const std::optional<QString> text = m_prompt(tr("Text label"), QString());
        if (!text || text->trimmed().isEmpty())
            return; // cancelled: nothing added
        made.text = text->trimmed().toStdString();
    }
    m_document.add(std::move(made));
    m_document.select(m_document.count() - 1);
}

void AnnotationToolController::finishDrag(QWidget& panel, QPoint position) {
    const Drag drag = *m_drag;
    m_drag.reset();
    if ((position - drag.pressedAt).manhattanLength() < QApplication::startDragDistance()) {
        repaint(); // a click on a handle: selected, not moved
        return;
    }
    const std::optional<glm::dvec3> point = anchorAt(panel, position);
    if (!point) {
        emit refused(noAnchorReason(panel, true));
        repaint();
        return;
    }
    m_document.moveAnchor(drag.annotation, drag.anchor, *point);
}

std::optional<glm::dvec3> AnnotationToolController::anchorAt(QWidget& panel,
                                                             QPoint position) const {
    if (auto* view = qobject_cast<SliceView*>(&panel))
        return view->patientAt(QPointF(position));
    return m_pick(static_cast<ReviewPanel&>(panel), position);
}

QString AnnotationToolController::noAnchorReason(QWidget& panel, bool dragging) const {
    if (qobject_cast<SliceView*>(&panel))
        return dragging ? tr("Not on the slice: the point stays where it was")
                        : tr("Not on the slice: click on the slice's image");
    return dragging ? tr("No surface under the pointer: the point stays where it was")
                    : tr("No surface under the pointer: click on the surface");
}

std::optional<AnnotationHit> AnnotationToolController::hitAt(QWidget& panel,
                                                             QPoint position) const {
    if (auto* view = qobject_cast<SliceView*>(&panel))
        return hitTestAnnotations(m_document.annotations(), sliceProjector(sliceFrame(*view)),
                                  glm::dvec2(position.x(), position.y()), kAnchorGrab, kLineGrab);
    auto& reviewPanel = static_cast<ReviewPanel&>(panel);
    const double ratio = reviewPanel.devicePixelRatioF();
    return hitTestAnnotations(m_document.annotations(), reviewPanel.viewCamera(),
                              reviewPanel.cameraPixel(position), kAnchorGrab * ratio,
                              kLineGrab * ratio);
}

std::optional<glm::dvec3> AnnotationToolController::pointerAtDepthOf(glm::dvec3 reference) const {
    if (auto* view = qobject_cast<SliceView*>(m_pointerPanel.data()))
        return view->patientAt(QPointF(m_pointer));
    auto* panel = qobject_cast<ReviewPanel*>(m_pointerPanel.data());
    if (!panel)
        return std::nullopt;
    const render::Camera camera = panel->viewCamera();
    const render::ProjectedPoint projected = camera.project(reference);
    if (!camera.isOrthographic() && projected.depth <= 0.0)
        return std::nullopt;
    return camera.unproject(panel->cameraPixel(m_pointer), projected.ndcDepth);
}

OverlayScene AnnotationToolController::scene() const {
    OverlayScene scene;
    scene.annotations = &m_document.annotations();
    scene.selected = m_document.selected();
    if (m_drag) {
        const annotation::Annotation& dragged = m_document.at(m_drag->annotation);
        const glm::dvec3 anchor = dragged.anchors.at(std::size_t(m_drag->anchor));
        if (const std::optional<glm::dvec3> at = pointerAtDepthOf(anchor)) {
            scene.preview = dragged;
            scene.preview->anchors[std::size_t(m_drag->anchor)] =
                dragged.slice ? annotation::pointOnSlice(*dragged.slice, *at) : *at;
            scene.previewReplaces = m_drag->annotation;
        }
    } else if (!m_pending.empty()) {
        if (const std::optional<glm::dvec3> at = pointerAtDepthOf(m_pending.back())) {
            const AnnotationKind kind = kindOf(m_tool);
            if (int(m_pending.size()) + 1 == annotation::anchorCount(kind)) {
                scene.preview = annotation::Annotation{kind, m_pending, {}, m_pendingSlice};
                scene.preview->anchors.push_back(*at);
            } else {
                scene.rubberBand = std::pair{m_pending.back(), *at};
            }
        }
    }
    return scene;
}

} // namespace lw::gui
