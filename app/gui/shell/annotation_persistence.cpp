#include "shell/annotation_persistence.h"

#include "annotate/annotation_document.h"
#include "lw/annotation/annotation_json.h"
#include "lw/core/error.h"
#include "lw/studydb/study_database.h"
#include "review/review_widget.h"

namespace lw::gui {

AnnotationPersistence::AnnotationPersistence(studydb::StudyDatabase& database, ReviewWidget& review)
    : QObject(&review), m_database(database), m_review(review),
      m_seriesUid(review.source().seriesUid) {
    load();
    // Connected after loading: the loaded list is not written back.
    connect(&m_review.annotations(), &AnnotationDocument::changed, this,
            &AnnotationPersistence::save);
}

void AnnotationPersistence::load() {
    try {
        const std::optional<QString> stored = m_database.seriesAnnotations(m_seriesUid);
        if (stored)
            m_review.annotations().reset(annotation::parseAnnotationsJson(
                stored->toStdString(), "the annotations of series " + m_seriesUid.toStdString() +
                                           " in " + m_database.path().toStdString()));
        m_saving = true;
    } catch (const core::Error& error) {
        fail(tr("Annotations not loaded, and not saved for this series so the stored ones are "
                "kept: %1")
                 .arg(QString::fromStdString(error.what())));
    }
}

void AnnotationPersistence::save() {
    if (!m_saving)
        return;
    try {
        m_database.setSeriesAnnotations(
            m_seriesUid, QString::fromStdString(
                             annotation::annotationsToJson(m_review.annotations().annotations())));
        m_review.setStorageProblem({});
    } catch (const core::Error& error) {
        // The edit stays on screen and in the undo history; the next change tries again.
        fail(tr("Annotations not saved: %1").arg(QString::fromStdString(error.what())));
    }
}

void AnnotationPersistence::fail(const QString& reason) {
    m_review.setStorageProblem(reason);
}

} // namespace lw::gui
