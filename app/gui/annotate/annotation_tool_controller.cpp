#include "annotate/annotation_tool_controller.h"

#include "annotate/annotation_commands.h"
#include "annotate/annotation_document.h"
#include "review/review_panel.h"

#include <QApplication>
#include <QEvent>
#include <QInputDialog>
#include <QMouseEvent>

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

void AnnotationToolController::attach(ReviewPanel& panel) {
    m_panels.emplace_back(&panel);
    panel.installEventFilter(this);
    panel.setOverlayPainter([this, &panel](QPainter& painter, const render::Camera& camera) {
        paintOverlay(painter, camera, scene(), panel.devicePixelRatioF());
    });
}

void AnnotationToolController::setTool(AnnotationTool tool) {
    m_pending.clear();
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
    for (const QPointer<ReviewPanel>& panel : m_panels)
        if (panel)
            panel->repaintOverlay();
}

bool AnnotationToolController::eventFilter(QObject* watched, QEvent* event) {
    auto* panel = qobject_cast<ReviewPanel*>(watched);
    if (!panel)
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

bool AnnotationToolController::mousePress(ReviewPanel& panel, QMouseEvent& event) {
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

bool AnnotationToolController::mouseMove(ReviewPanel& panel, QMouseEvent& event) {
    m_pointerPanel = &panel;
    m_pointer = event.position().toPoint();
    if (m_drag || !m_pending.empty())
        repaint(); // the preview follows the mouse
    return m_swallowDrag && (event.buttons() & Qt::LeftButton);
}

bool AnnotationToolController::mouseRelease(ReviewPanel& panel, QMouseEvent& event) {
    if (event.button() != Qt::LeftButton || !m_swallowDrag)
        return false;
    m_swallowDrag = false;
    if (m_drag)
        finishDrag(panel, event.position().toPoint());
    return true;
}

bool AnnotationToolController::doubleClick(ReviewPanel& panel, QMouseEvent& event) {
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

void AnnotationToolController::placeAnchor(ReviewPanel& panel, QPoint position) {
    const std::optional<glm::dvec3> point = m_pick(panel, position);
    if (!point) {
        emit refused(tr("No surface under the pointer: click on the surface"));
        return;
    }
    m_pending.push_back(*point);
    if (int(m_pending.size()) == annotation::anchorCount(kindOf(m_tool)))
        finishPlacement();
    announcePrompt();
    repaint();
}

void AnnotationToolController::finishPlacement() {
    annotation::Annotation made{kindOf(m_tool), std::move(m_pending), {}};
    m_pending.clear();
    if (made.kind == AnnotationKind::Label) {
        const std::optional<QString> text = m_prompt(tr("Text label"), QString());
        if (!text || text->trimmed().isEmpty())
            return; // cancelled: nothing added
        made.text = text->trimmed().toStdString();
    }
    m_document.add(std::move(made));
    m_document.select(m_document.count() - 1);
}

void AnnotationToolController::finishDrag(ReviewPanel& panel, QPoint position) {
    const Drag drag = *m_drag;
    m_drag.reset();
    if ((position - drag.pressedAt).manhattanLength() < QApplication::startDragDistance()) {
        repaint(); // a click on a handle: selected, not moved
        return;
    }
    const std::optional<glm::dvec3> point = m_pick(panel, position);
    if (!point) {
        emit refused(tr("No surface under the pointer: the point stays where it was"));
        repaint();
        return;
    }
    m_document.moveAnchor(drag.annotation, drag.anchor, *point);
}

std::optional<AnnotationHit> AnnotationToolController::hitAt(ReviewPanel& panel,
                                                             QPoint position) const {
    const double ratio = panel.devicePixelRatioF();
    return hitTestAnnotations(m_document.annotations(), panel.viewCamera(),
                              panel.cameraPixel(position), kAnchorGrab * ratio, kLineGrab * ratio);
}

std::optional<glm::dvec3> AnnotationToolController::pointerAtDepthOf(glm::dvec3 reference) const {
    if (!m_pointerPanel)
        return std::nullopt;
    const render::Camera camera = m_pointerPanel->viewCamera();
    const render::ProjectedPoint projected = camera.project(reference);
    if (!camera.isOrthographic() && projected.depth <= 0.0)
        return std::nullopt;
    return camera.unproject(m_pointerPanel->cameraPixel(m_pointer), projected.ndcDepth);
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
            scene.preview->anchors[std::size_t(m_drag->anchor)] = *at;
            scene.previewReplaces = m_drag->annotation;
        }
    } else if (!m_pending.empty()) {
        if (const std::optional<glm::dvec3> at = pointerAtDepthOf(m_pending.back())) {
            const AnnotationKind kind = kindOf(m_tool);
            if (int(m_pending.size()) + 1 == annotation::anchorCount(kind)) {
                scene.preview = annotation::Annotation{kind, m_pending, {}};
                scene.preview->anchors.push_back(*at);
            } else {
                scene.rubberBand = std::pair{m_pending.back(), *at};
            }
        }
    }
    return scene;
}

} // namespace lw::gui
