#pragma once

// Turns the mouse on the review's panels into annotation edits. With a tool (text label, arrow,
// ruler, angle) each left click picks an anchor on the iso-surface under it (patient coordinates,
// so the annotation follows the camera); the last anchor completes it (a label asks for its text
// first). Between clicks the camera still zooms, pans and turns (wheel, right and middle drag,
// keys, the view buttons), so a ruler can span what one view does not show. Without a tool a
// click on an annotation selects it and dragging one of its anchors moves it (re-picked where it
// is dropped); any other drag turns the camera as before. Esc drops the annotation being placed,
// then the tool, then the selection.
//
// On a slice panel a click places the anchor on the slice itself (SliceView::patientAt), and the
// annotation remembers the slice (annotation::SlicePlacement): every anchor of one annotation is
// clicked on the same slice, and dragging an anchor (on a slice or in 3D) keeps it on that plane
// (annotation::pointOnSlice). A slice shows the annotations annotation::showsOnSlice keeps; the
// 3D panels show them all. The slices' other buttons (wheel, right and middle drag, Shift+click)
// keep their meaning.
//
// It filters the panels' events and paints through their overlay hook, so ReviewPanel and
// SliceView know nothing of annotations.

#include "annotate/annotation_hit_test.h"
#include "annotate/overlay_painter.h"

#include <QObject>
#include <QPoint>
#include <QPointer>
#include <QString>
#include <QWidget>
#include <functional>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

class QMouseEvent;

namespace lw::gui {

class AnnotationDocument;
class ReviewPanel;
class SliceView;

enum class AnnotationTool { None, Label, Arrow, Ruler, Angle };

class AnnotationToolController : public QObject {
    Q_OBJECT
public:
    // The surface point under a widget position of a panel (nullopt: no surface there).
    using Picker = std::function<std::optional<glm::dvec3>(ReviewPanel& panel, QPoint position)>;
    // Asks for a text (a label's, or a caption); nullopt when the user cancels.
    using TextPrompt =
        std::function<std::optional<QString>(const QString& title, const QString& initial)>;

    AnnotationToolController(AnnotationDocument& document, Picker pick, QObject* parent = nullptr);

    // Filters the panel's mouse events and draws the annotations over it.
    void attach(ReviewPanel& panel);
    void attach(SliceView& view);
    // The dialog that asks for texts (tests answer it themselves).
    void setTextPrompt(TextPrompt prompt) { m_prompt = std::move(prompt); }

    AnnotationTool tool() const { return m_tool; }
    // What to do next, for the review's hint line; empty without a tool.
    QString prompt() const;
    int pendingAnchors() const { return int(m_pending.size()); }

public slots:
    void setTool(lw::gui::AnnotationTool tool);
    void cancel();
    void deleteSelected();
    void editSelectedText();

signals:
    void toolChanged(lw::gui::AnnotationTool tool);
    void promptChanged(const QString& prompt);
    // A click that did nothing, and why ("no surface under the pointer").
    void refused(const QString& reason);

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    struct Drag {
        int annotation = -1;
        int anchor = -1;
        QPoint pressedAt; // a click without a drag selects and moves nothing
    };

    // `panel`: a ReviewPanel or a SliceView attached.
    bool mousePress(QWidget& panel, QMouseEvent& event);
    bool mouseMove(QWidget& panel, QMouseEvent& event);
    bool mouseRelease(QWidget& panel, QMouseEvent& event);
    bool doubleClick(QWidget& panel, QMouseEvent& event);
    void placeAnchor(QWidget& panel, QPoint position);
    void finishPlacement();
    void finishDrag(QWidget& panel, QPoint position);
    // Where a click puts an anchor: the surface under it in 3D, the slice's point on a slice.
    std::optional<glm::dvec3> anchorAt(QWidget& panel, QPoint position) const;
    QString noAnchorReason(QWidget& panel, bool dragging) const; // why a click placed nothing
    std::optional<AnnotationHit> hitAt(QWidget& panel, QPoint position) const;
    // The patient point under the pointer at the depth of `reference`: where an anchor would go
    // if dropped now, before the surface is picked (on a slice: the slice's point).
    std::optional<glm::dvec3> pointerAtDepthOf(glm::dvec3 reference) const;
    OverlayScene scene() const;
    void repaint();
    void announcePrompt();

    AnnotationDocument& m_document;
    Picker m_pick;
    TextPrompt m_prompt;
    std::vector<QPointer<QWidget>> m_panels;
    AnnotationTool m_tool = AnnotationTool::None;
    std::vector<glm::dvec3> m_pending; // anchors placed of the annotation being made
    std::optional<annotation::SlicePlacement> m_pendingSlice; // the slice they were placed on
    std::optional<Drag> m_drag;
    bool m_swallowDrag = false; // a left press we took: its drag must not turn the camera
    QPointer<QWidget> m_pointerPanel;
    QPoint m_pointer;
};

} // namespace lw::gui
