#include "app/editor/ExportHairDialog.h"

#include "io/HairFiles.h"

#include <QButtonGroup>
#include <QDialogButtonBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLineEdit>
#include <QPushButton>
#include <QRadioButton>
#include <QVBoxLayout>

#include <algorithm>

namespace wisp {

HairCurves strandsForExport(const Frame& frame, const HairExportChoice& choice)
{
    const HairCurves& source
        = choice.restPose && frame.groomShape ? frame.groomShape->rest.anySpace() : frame.strands.anySpace();
    if (!choice.keysOnly)
        return source;
    HairCurves keys;
    if (!frame.groomShape)
        return keys;
    for (std::uint32_t k : frame.groomShape->keyStrands) {
        if (k >= source.strandCount())
            continue;
        const auto points = source.strand(k);
        const std::size_t index = keys.addStrand(static_cast<std::uint32_t>(points.size()));
        std::copy(points.begin(), points.end(), keys.strandForWrite(index).begin());
    }
    return keys;
}

QString ExportHairDialog::fileFilter()
{
    return tr("cyHair (*.hair);;USC-HairSalon (*.data);;OBJ polylines (*.obj);;glTF (*.gltf);;binary glTF (*.glb)");
}

ExportHairDialog::ExportHairDialog(QWidget* parent)
    : QDialog(parent)
{
    setWindowTitle(tr("Export Hair"));
    auto* layout = new QVBoxLayout(this);
    auto* form = new QFormLayout;
    auto* pathRow = new QHBoxLayout;
    m_path = new QLineEdit;
    m_path->setToolTip(tr("The extension picks the format: .hair, .data, .obj, .gltf or .glb (the last three "
                          "include the head)"));
    auto* browse = new QPushButton(tr("Browse…"));
    pathRow->addWidget(m_path);
    pathRow->addWidget(browse);
    form->addRow(tr("File"), pathRow);

    auto* frameButton = new QRadioButton(tr("Current frame"));
    m_rest = new QRadioButton(tr("Rest pose"));
    frameButton->setChecked(true);
    frameButton->setToolTip(tr("The hair as it hangs now, in world space"));
    m_rest->setToolTip(tr("The groom before any force acts on it, in head space"));
    auto* poseGroup = new QButtonGroup(this);
    poseGroup->addButton(frameButton);
    poseGroup->addButton(m_rest);
    auto* poseRow = new QHBoxLayout;
    poseRow->addWidget(frameButton);
    poseRow->addWidget(m_rest);
    form->addRow(tr("Pose"), poseRow);

    auto* allButton = new QRadioButton(tr("Every drawn strand"));
    m_keys = new QRadioButton(tr("Key hairs only"));
    allButton->setChecked(true);
    m_keys->setToolTip(tr("One strand per wisp: the simulated guides"));
    auto* whichGroup = new QButtonGroup(this);
    whichGroup->addButton(allButton);
    whichGroup->addButton(m_keys);
    auto* whichRow = new QHBoxLayout;
    whichRow->addWidget(allButton);
    whichRow->addWidget(m_keys);
    form->addRow(tr("Strands"), whichRow);
    layout->addLayout(form);

    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    buttons->button(QDialogButtonBox::Ok)->setText(tr("Export"));
    layout->addWidget(buttons);
    connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    connect(browse, &QPushButton::clicked, this, [this] {
        const QString chosen = QFileDialog::getSaveFileName(this, tr("Export Hair"), m_path->text(), fileFilter());
        if (!chosen.isEmpty())
            m_path->setText(chosen);
    });
    const auto updateOk = [this, buttons] {
        buttons->button(QDialogButtonBox::Ok)
            ->setEnabled(io::hairFormatForPath(m_path->text().toStdString()).has_value());
    };
    connect(m_path, &QLineEdit::textChanged, this, updateOk);
    updateOk();
}

QString ExportHairDialog::path() const
{
    return m_path->text();
}
void ExportHairDialog::setPath(const QString& path)
{
    m_path->setText(path);
}

HairExportChoice ExportHairDialog::choice() const
{
    return { m_rest->isChecked(), m_keys->isChecked() };
}

} // namespace wisp
