#include "annotate/annotation_actions.h"

#include <QAction>
#include <QActionGroup>
#include <QWidget>

namespace lw::gui {

AnnotationActions::AnnotationActions(AnnotationToolController& tools, QWidget& scope)
    : QObject(&scope), m_tools(tools) {
    m_group = new QActionGroup(this);
    m_group->setExclusionPolicy(QActionGroup::ExclusionPolicy::ExclusiveOptional);
    addToolAction(scope, AnnotationTool::Label, tr("&Text label"), tr("T"), "textLabelTool");
    addToolAction(scope, AnnotationTool::Arrow, tr("&Arrow"), tr("A"), "arrowTool");
    addToolAction(scope, AnnotationTool::Ruler, tr("&Ruler"), tr("R"), "rulerTool");
    addToolAction(scope, AnnotationTool::Angle, tr("An&gle"), tr("G"), "angleTool");
    m_cancel =
        addCommand(scope, tr("&Cancel tool"), QKeySequence(Qt::Key_Escape), "cancelAnnotationTool");
    connect(m_cancel, &QAction::triggered, &m_tools, &AnnotationToolController::cancel);
    m_delete =
        addCommand(scope, tr("&Delete annotation"), QKeySequence::Delete, "deleteAnnotation");
    connect(m_delete, &QAction::triggered, &m_tools, &AnnotationToolController::deleteSelected);
    m_editText =
        addCommand(scope, tr("&Edit text…"), QKeySequence(Qt::Key_F2), "editAnnotationText");
    connect(m_editText, &QAction::triggered, &m_tools, &AnnotationToolController::editSelectedText);
    // The buttons show which tool is on, whoever turned it on or off.
    connect(&m_tools, &AnnotationToolController::toolChanged, this, [this](AnnotationTool tool) {
        for (QAction* action : m_toolActions)
            action->setChecked(action->data().toInt() == int(tool));
    });
}

QAction* AnnotationActions::addToolAction(QWidget& scope, AnnotationTool tool, const QString& text,
                                          const QString& key, const QString& name) {
    QAction* action = addCommand(scope, text, QKeySequence(key), name);
    action->setCheckable(true);
    action->setData(int(tool));
    action->setActionGroup(m_group);
    connect(action, &QAction::triggered, this,
            [this, tool](bool checked) { m_tools.setTool(checked ? tool : AnnotationTool::None); });
    m_toolActions.append(action);
    return action;
}

QAction* AnnotationActions::addCommand(QWidget& scope, const QString& text, const QKeySequence& key,
                                       const QString& name) {
    auto* action = new QAction(text, this);
    action->setObjectName(name);
    action->setShortcut(key);
    action->setShortcutContext(Qt::WidgetWithChildrenShortcut);
    action->setToolTip(QStringLiteral("%1 (%2)").arg(QString(text).remove('&').remove(u'…'),
                                                     key.toString(QKeySequence::NativeText)));
    scope.addAction(action);
    return action;
}

} // namespace lw::gui
