#pragma once

// The annotations of one review (anchored in patient coordinates, lw::annotation) and which one
// is selected, with their undo history. Every edit is one command on the undo stack (add, move an
// anchor, edit the text, delete), so Ctrl+Z restores exactly the state before it; `changed`
// follows each edit, undo and redo, which is when the study database saves them.

#include "lw/annotation/annotation.h"

#include <QObject>
#include <QUndoStack>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace lw::gui {

class AnnotationDocument : public QObject {
    Q_OBJECT
public:
    explicit AnnotationDocument(QObject* parent = nullptr);

    const std::vector<annotation::Annotation>& annotations() const { return m_annotations; }
    int count() const { return int(m_annotations.size()); }
    const annotation::Annotation& at(int index) const {
        return m_annotations.at(std::size_t(index));
    }
    QUndoStack& undoStack() { return m_undoStack; }

    // -1 when none is selected.
    int selected() const { return m_selected; }
    void select(int index);

    // The edits, each one undoable command. Anchors are patient coordinates (LPS, mm); a moved
    // anchor of an annotation placed on a slice goes onto its plane (annotation::pointOnSlice).
    void add(annotation::Annotation annotation);
    void remove(int index);
    void moveAnchor(int index, int anchor, glm::dvec3 point);
    void setText(int index, const std::string& text);
    // Everything replaced without history: the annotations stored with the series, on opening.
    void reset(std::vector<annotation::Annotation> annotations);

signals:
    void changed(); // the annotations changed (not only the selection)
    void selectionChanged();

private:
    friend class AnnotationEdit; // the undo command applies its edit through these
    void insertAt(int index, annotation::Annotation annotation);
    void removeAt(int index);
    void replaceAt(int index, annotation::Annotation annotation);

    std::vector<annotation::Annotation> m_annotations;
    int m_selected = -1;
    QUndoStack m_undoStack;
};

} // namespace lw::gui
