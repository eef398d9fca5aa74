#pragma once
// File ▸ Export Hair: where to (.hair, .data, .obj, .gltf, .glb), and what: the current frame or
// the rest pose, every drawn strand or the key hairs only. The head goes along in .obj and glTF.
//
// Thread: GUI.

#include "sim/solver/Frame.h"

#include <QDialog>

class QLineEdit;
class QRadioButton;

namespace wisp {

struct HairExportChoice {
    bool restPose = false; // false: the frame as it is now
    bool keysOnly = false; // false: every drawn strand
};

// The strands an export writes, from a published frame (world space) or its groom's rest pose
// (head space). Empty when the frame has no groom shape to take them from.
HairCurves strandsForExport(const Frame& frame, const HairExportChoice& choice);

class ExportHairDialog : public QDialog {
    Q_OBJECT
public:
    explicit ExportHairDialog(QWidget* parent = nullptr);

    QString path() const;
    void setPath(const QString& path);
    HairExportChoice choice() const;

    QRadioButton* restPoseButton() const { return m_rest; }
    QRadioButton* keysOnlyButton() const { return m_keys; }

    static QString fileFilter(); // for the file dialog

private:
    QLineEdit* m_path = nullptr;
    QRadioButton* m_rest = nullptr;
    QRadioButton* m_keys = nullptr;
};

} // namespace wisp
