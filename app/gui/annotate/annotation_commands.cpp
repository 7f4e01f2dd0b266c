#include "annotate/annotation_commands.h"

#include "annotate/annotation_document.h"

#include <QCoreApplication>

namespace lw::gui {

AnnotationEdit::AnnotationEdit(AnnotationDocument& document, int index,
                               std::optional<annotation::Annotation> before,
                               std::optional<annotation::Annotation> after, const QString& text)
    : QUndoCommand(text), m_document(document), m_index(index), m_before(std::move(before)),
      m_after(std::move(after)) {}

void AnnotationEdit::redo() {
    apply(m_before, m_after);
}

void AnnotationEdit::undo() {
    apply(m_after, m_before);
}

void AnnotationEdit::apply(const std::optional<annotation::Annotation>& from,
                           const std::optional<annotation::Annotation>& to) {
    if (!from && to)
        m_document.insertAt(m_index, *to);
    else if (from && !to)
        m_document.removeAt(m_index);
    else if (to)
        m_document.replaceAt(m_index, *to);
    // What the edit touched is selected, so the user sees what undo or redo did.
    m_document.select(to ? m_index : -1);
}

QString annotationKindLabel(annotation::AnnotationKind kind) {
    switch (kind) {
    case annotation::AnnotationKind::Label:
        return QCoreApplication::translate("lw::gui::Annotations", "text label");
    case annotation::AnnotationKind::Arrow:
        return QCoreApplication::translate("lw::gui::Annotations", "arrow");
    case annotation::AnnotationKind::Ruler:
        return QCoreApplication::translate("lw::gui::Annotations", "ruler");
    case annotation::AnnotationKind::Angle:
        return QCoreApplication::translate("lw::gui::Annotations", "angle");
    }
    return {};
}

} // namespace lw::gui
