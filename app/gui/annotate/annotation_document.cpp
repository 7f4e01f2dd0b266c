#include "annotate/annotation_document.h"

#include "annotate/annotation_commands.h"

namespace lw::gui {

AnnotationDocument::AnnotationDocument(QObject* parent) : QObject(parent) {}

void AnnotationDocument::select(int index) {
    const int valid = index >= 0 && index < count() ? index : -1;
    if (valid == m_selected)
        return;
    m_selected = valid;
    emit selectionChanged();
}

void AnnotationDocument::add(annotation::Annotation annotation) {
    const QString what = tr("Add %1").arg(annotationKindLabel(annotation.kind));
    m_undoStack.push(new AnnotationEdit(*this, count(), std::nullopt, std::move(annotation), what));
}

void AnnotationDocument::remove(int index) {
    const annotation::Annotation& item = at(index);
    m_undoStack.push(new AnnotationEdit(*this, index, item, std::nullopt,
                                        tr("Delete %1").arg(annotationKindLabel(item.kind))));
}

void AnnotationDocument::moveAnchor(int index, int anchor, glm::dvec3 point) {
    const QString what = tr("Move %1 point").arg(annotationKindLabel(at(index).kind));
    annotation::Annotation moved = at(index);
    // An annotation placed on a slice stays on its plane wherever the point is dropped.
    moved.anchors.at(std::size_t(anchor)) =
        moved.slice ? annotation::pointOnSlice(*moved.slice, point) : point;
    m_undoStack.push(new AnnotationEdit(*this, index, at(index), std::move(moved), what));
}

void AnnotationDocument::setText(int index, const std::string& text) {
    annotation::Annotation edited = at(index);
    if (edited.text == text)
        return; // nothing to undo
    edited.text = text;
    const QString what = tr("Edit %1 text").arg(annotationKindLabel(edited.kind));
    m_undoStack.push(new AnnotationEdit(*this, index, at(index), std::move(edited), what));
}

void AnnotationDocument::reset(std::vector<annotation::Annotation> annotations) {
    m_undoStack.clear(); // commands refer to indexes of the list being replaced
    m_annotations = std::move(annotations);
    select(-1);
    emit changed();
}

void AnnotationDocument::insertAt(int index, annotation::Annotation annotation) {
    m_annotations.insert(m_annotations.begin() + index, std::move(annotation));
    if (m_selected >= index)
        ++m_selected;
    emit changed();
}

void AnnotationDocument::removeAt(int index) {
    m_annotations.erase(m_annotations.begin() + index);
    if (m_selected == index)
        select(-1);
    else if (m_selected > index)
        --m_selected;
    emit changed();
}

void AnnotationDocument::replaceAt(int index, annotation::Annotation annotation) {
    m_annotations.at(std::size_t(index)) = std::move(annotation);
    emit changed();
}

} // namespace lw::gui
