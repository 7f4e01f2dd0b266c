#pragma once

// The undo command of the annotation document: one edit of one annotation, as the annotation
// before and after it (absent before an add, absent after a delete). Keeping whole annotations
// rather than deltas makes undo exact: a moved anchor comes back to the very point it was
// picked at, and a deleted ruler returns at its place in the list (the report's table order).

#include "lw/annotation/annotation.h"

#include <QUndoCommand>
#include <optional>

namespace lw::gui {

class AnnotationDocument;

class AnnotationEdit : public QUndoCommand {
public:
    AnnotationEdit(AnnotationDocument& document, int index,
                   std::optional<annotation::Annotation> before,
                   std::optional<annotation::Annotation> after, const QString& text);

    void redo() override;
    void undo() override;

private:
    void apply(const std::optional<annotation::Annotation>& from,
               const std::optional<annotation::Annotation>& to);

    AnnotationDocument& m_document;
    int m_index;
    std::optional<annotation::Annotation> m_before;
    std::optional<annotation::Annotation> m_after;
};

// "ruler", "angle", ... as the menus and the undo history name it (translated).
QString annotationKindLabel(annotation::AnnotationKind kind);

} // namespace lw::gui
