#pragma once

// Keeps a review's annotations with its series in the study database: loaded when the review
// opens, saved after every change (each save one transaction, the whole list as the annotation
// JSON of modules/annotation), so closing the window or a crash loses at most the edit being
// made. A stored text that no longer parses is shown as an error and left as it is: saving stays
// off for that series rather than overwrite what the user had.

#include <QObject>
#include <QString>

namespace lw::studydb {
class StudyDatabase;
}

namespace lw::gui {

class ReviewWidget;

class AnnotationPersistence : public QObject {
    Q_OBJECT
public:
    // Loads the annotations of the review's series (it must have a series UID) into the review and
    // saves them from now on. The database must outlive the review (the main window closes its
    // reviews before the browser that owns it).
    AnnotationPersistence(studydb::StudyDatabase& database, ReviewWidget& review);

    bool isSaving() const { return m_saving; }

private:
    void load();
    void save();
    void fail(const QString& reason);

    studydb::StudyDatabase& m_database;
    ReviewWidget& m_review;
    QString m_seriesUid;
    bool m_saving = false;
};

} // namespace lw::gui
