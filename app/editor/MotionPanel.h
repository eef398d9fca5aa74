#pragma once
// The Motion panel: the head's procedural motion (kind, amplitude, frequency) and its keys (Set
// Key from the head's current pose at the current time, Delete Key, a key's time). Every edit is
// one undo step through Document::setHeadMotion; a refused edit puts the panel back and says why
// (message). It shows the document's motion again after every change (an edit, undo, a project).
//
// Thread: GUI.

#include <QWidget>

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QListWidget;
class QPushButton;

namespace wisp {

class Document;
class HeadMoveTool;
class HeadMotion;

class MotionPanel : public QWidget {
    Q_OBJECT
public:
    MotionPanel(Document* document, HeadMoveTool* headTool, QWidget* parent = nullptr);

    QComboBox* kindBox() const { return m_kind; }
    QDoubleSpinBox* amplitudeBox() const { return m_amplitude; }
    QDoubleSpinBox* frequencyBox() const { return m_frequency; }
    QListWidget* keyList() const { return m_keys; }
    QDoubleSpinBox* keyTimeBox() const { return m_keyTime; } // the selected key's time, seconds
    QPushButton* setKeyButton() const { return m_setKey; }
    QPushButton* deleteKeyButton() const { return m_deleteKey; }

signals:
    void message(const QString& text);
    // The artist selected a key (or moved the selected one): the timeline goes to its time, as
    // Blender's dopesheet moves the current frame.
    void keySelected(double seconds);

private:
    void showMotion();
    void proceduralEdited();
    void kindChosen(int index);
    void setKey();
    void deleteKey();
    void keyTimeEdited();
    void apply(const HeadMotion& motion, const QString& text);

    Document* m_document;
    HeadMoveTool* m_headTool;
    QComboBox* m_kind = nullptr;
    QDoubleSpinBox* m_amplitude = nullptr;
    QDoubleSpinBox* m_frequency = nullptr;
    QListWidget* m_keys = nullptr;
    QDoubleSpinBox* m_keyTime = nullptr;
    QPushButton* m_setKey = nullptr;
    QPushButton* m_deleteKey = nullptr;
    bool m_showing = false;
};

} // namespace wisp
