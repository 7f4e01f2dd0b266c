#pragma once

// The annotation commands as actions with their keys, live while the focus is in the review
// they belong to (Qt::WidgetWithChildrenShortcut, so two open reviews never fight over a key and
// the study browser keeps its own Del): T text label, A arrow, R ruler, G angle (one tool at a
// time; the checked one again puts it away), Esc cancel, Del delete the selected annotation,
// F2 edit its text. The review's bar shows the four tools as buttons and the main window lists
// all of them in its Annotate menu.

#include "annotate/annotation_tool_controller.h"

#include <QList>
#include <QObject>

class QAction;
class QActionGroup;
class QWidget;

namespace lw::gui {

class AnnotationActions : public QObject {
    Q_OBJECT
public:
    // The actions are added to `scope`, whose focus chain decides when their keys work.
    AnnotationActions(AnnotationToolController& tools, QWidget& scope);

    const QList<QAction*>& toolActions() const { return m_toolActions; }
    QAction* cancelAction() const { return m_cancel; }
    QAction* deleteAction() const { return m_delete; }
    QAction* editTextAction() const { return m_editText; }

private:
    QAction* addToolAction(QWidget& scope, AnnotationTool tool, const QString& text,
                           const QString& key, const QString& name);
    QAction* addCommand(QWidget& scope, const QString& text, const QKeySequence& key,
                        const QString& name);

    AnnotationToolController& m_tools;
    QActionGroup* m_group = nullptr;
    QList<QAction*> m_toolActions;
    QAction* m_cancel = nullptr;
    QAction* m_delete = nullptr;
    QAction* m_editText = nullptr;
};

} // namespace lw::gui
