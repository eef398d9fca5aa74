#include "app/editor/MotionPanel.h"

#include "app/editor/Document.h"
#include "app/editor/HeadMoveTool.h"
#include "sim/motion/FrameTime.h"
#include "sim/motion/HeadMotion.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QListWidget>
#include <QPushButton>
#include <QSignalBlocker>
#include <QVBoxLayout>

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <iterator>

namespace wisp {

namespace {

constexpr MotionKind kKinds[]
    = { MotionKind::None, MotionKind::Turn, MotionKind::Nod, MotionKind::Shake, MotionKind::Walk };

bool inMetres(MotionKind kind)
{
    return kind == MotionKind::Walk;
}

QString text(std::string_view s)
{
    return QString::fromUtf8(s.data(), static_cast<qsizetype>(s.size()));
}

// A spin box's range and tooltip from the registry's motion setting (sim/params/Parameters.h):
// "<help>, <min> to <max> <unit>". `minimum` may raise the low end (key times start at 0 s in the
// panel, where the timeline starts).
void takeRange(QDoubleSpinBox* box, MotionSetting setting, double minimum = -INFINITY)
{
    const MotionSettingInfo& info = motionSettingInfo(setting);
    const double low = std::max(info.minimum, minimum);
    box->setRange(low, info.maximum);
    box->setToolTip(
        QStringLiteral("%1, %2 to %3 %4").arg(text(info.help)).arg(low).arg(info.maximum).arg(text(info.unit)));
}

QString keyText(const HeadKey& key)
{
    // Short enough for the dock: the time, the turn as X Y Z angles (degrees) and the move (cm).
    const glm::vec3 degrees = glm::degrees(glm::eulerAngles(key.pose.rotation));
    const glm::vec3 cm = key.pose.translationMetres * 100.0f;
    return QStringLiteral("%1 s  turn %2° %3° %4°  move %5 %6 %7 cm")
        .arg(key.timeSeconds, 0, 'f', 3)
        .arg(degrees.x, 0, 'f', 0)
        .arg(degrees.y, 0, 'f', 0)
        .arg(degrees.z, 0, 'f', 0)
        .arg(cm.x, 0, 'f', 1)
        .arg(cm.y, 0, 'f', 1)
        .arg(cm.z, 0, 'f', 1);
}

} // namespace

MotionPanel::MotionPanel(Document* document, HeadMoveTool* headTool, QWidget* parent)
    : QWidget(parent)
    , m_document(document)
    , m_headTool(headTool)
{
    auto* form = new QFormLayout;
    m_kind = new QComboBox(this);
    m_kind->setObjectName(QStringLiteral("motionKind"));
    for (MotionKind kind : kKinds)
        m_kind->addItem(QString::fromUtf8(motionName(kind).data(), static_cast<int>(motionName(kind).size())));
    m_kind->setToolTip(tr("A repeating head motion: turn and shake turn the head left and right, nod tilts it, "
                          "walk bobs and sways it"));
    form->addRow(tr("Motion"), m_kind);
    m_amplitude = new QDoubleSpinBox(this);
    m_amplitude->setObjectName(QStringLiteral("motionAmplitude"));
    m_amplitude->setDecimals(3);
    m_amplitude->setKeyboardTracking(false);
    form->addRow(tr("Amplitude"), m_amplitude);
    m_frequency = new QDoubleSpinBox(this);
    m_frequency->setObjectName(QStringLiteral("motionFrequency"));
    takeRange(m_frequency, MotionSetting::Frequency);
    m_frequency->setDecimals(2);
    m_frequency->setSuffix(tr(" Hz"));
    m_frequency->setKeyboardTracking(false);
    form->addRow(tr("Frequency"), m_frequency);

    m_keys = new QListWidget(this);
    m_keys->setObjectName(QStringLiteral("motionKeys"));
    m_keys->setToolTip(tr("The head's keys: Ctrl+Alt+drag in the viewport turns the head and keys it"));
    m_keyTime = new QDoubleSpinBox(this);
    m_keyTime->setObjectName(QStringLiteral("motionKeyTime"));
    takeRange(m_keyTime, MotionSetting::Time, 0.0);
    m_keyTime->setToolTip(m_keyTime->toolTip() + tr(" (moved to the timeline's nearest frame)"));
    m_keyTime->setDecimals(3);
    m_keyTime->setSuffix(tr(" s"));
    m_keyTime->setKeyboardTracking(false);
    m_setKey = new QPushButton(tr("Set Key"), this);
    m_setKey->setToolTip(tr("Key the head's current pose at the current time"));
    m_deleteKey = new QPushButton(tr("Delete Key"), this);
    auto* buttons = new QHBoxLayout;
    buttons->addWidget(m_setKey);
    buttons->addWidget(m_deleteKey);
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(form);
    layout->addWidget(m_keys);
    auto* timeForm = new QFormLayout;
    timeForm->addRow(tr("Key time"), m_keyTime);
    layout->addLayout(timeForm);
    layout->addLayout(buttons);
    layout->addStretch(1);

    connect(m_kind, &QComboBox::activated, this, &MotionPanel::kindChosen);
    connect(m_amplitude, &QDoubleSpinBox::valueChanged, this, &MotionPanel::proceduralEdited);
    connect(m_frequency, &QDoubleSpinBox::valueChanged, this, &MotionPanel::proceduralEdited);
    connect(m_keyTime, &QDoubleSpinBox::valueChanged, this, &MotionPanel::keyTimeEdited);
    connect(m_setKey, &QPushButton::clicked, this, &MotionPanel::setKey);
    connect(m_deleteKey, &QPushButton::clicked, this, &MotionPanel::deleteKey);
    connect(m_keys, &QListWidget::currentRowChanged, this, [this](int row) {
        const auto& keys = m_document->headMotion().keys();
        m_deleteKey->setEnabled(row >= 0);
        m_keyTime->setEnabled(row >= 0);
        if (row >= 0 && row < static_cast<int>(keys.size())) {
            const QSignalBlocker block(m_keyTime);
            m_keyTime->setValue(keys[static_cast<std::size_t>(row)].timeSeconds);
            emit keySelected(keys[static_cast<std::size_t>(row)].timeSeconds);
        }
    });
    connect(m_document, &Document::headMotionChanged, this, &MotionPanel::showMotion);
    showMotion();
}

void MotionPanel::showMotion()
{
    const HeadMotion& motion = m_document->headMotion();
    const ProceduralMotion& p = motion.procedural();
    const QSignalBlocker a(m_kind), b(m_amplitude), c(m_frequency), d(m_keys), e(m_keyTime);
    m_kind->setCurrentIndex(static_cast<int>(p.kind));
    const bool metres = inMetres(p.kind);
    takeRange(m_amplitude, amplitudeSettingOf(p.kind));
    m_amplitude->setSuffix(metres ? tr(" m") : tr("°"));
    m_amplitude->setValue(p.amplitude);
    m_frequency->setValue(p.frequencyHz);
    m_amplitude->setEnabled(p.kind != MotionKind::None);
    m_frequency->setEnabled(p.kind != MotionKind::None);
    const int row = m_keys->currentRow();
    m_keys->clear();
    for (const HeadKey& key : motion.keys())
        m_keys->addItem(keyText(key));
    m_keys->setCurrentRow(std::min(row, m_keys->count() - 1));
    m_deleteKey->setEnabled(m_keys->currentRow() >= 0);
    m_keyTime->setEnabled(m_keys->currentRow() >= 0);
    if (m_keys->currentRow() >= 0)
        m_keyTime->setValue(motion.keys()[static_cast<std::size_t>(m_keys->currentRow())].timeSeconds);
}

void MotionPanel::apply(const HeadMotion& motion, const QString& text)
{
    const QString refused = m_document->setHeadMotion(motion, text);
    if (!refused.isEmpty()) {
        emit message(refused);
        showMotion(); // back to what the document has
    }
}

void MotionPanel::kindChosen(int index)
{
    if (index < 0 || index >= static_cast<int>(std::size(kKinds)))
        return;
    HeadMotion motion = m_document->headMotion();
    if (motion.procedural().kind == kKinds[index])
        return;
    ProceduralMotion p = motionPreset(kKinds[index]); // amplitudes differ in unit between kinds
    p.startSeconds = m_headTool->currentSeconds(); // fades in from now, not from a past start
    motion.setProcedural(p);
    apply(motion, tr("Head Motion: %1").arg(m_kind->itemText(index)));
}

void MotionPanel::proceduralEdited()
{
    HeadMotion motion = m_document->headMotion();
    ProceduralMotion p = motion.procedural();
    p.amplitude = m_amplitude->value();
    p.frequencyHz = m_frequency->value();
    if (p == motion.procedural())
        return;
    motion.setProcedural(p);
    apply(motion, tr("Head Motion Amplitude/Frequency"));
}

void MotionPanel::setKey()
{
    // At the current time on the timeline's frame (unlike a drag on a motion without keys, which
    // keys 0 s: here the artist asks for a key now).
    HeadMotion motion = m_document->headMotion();
    const double t = m_headTool->currentSeconds();
    const double fps = m_document->timeline().fps;
    motion.setKey(snappedToFrame(t, fps), motion.keyedPoseAt(t));
    apply(motion, tr("Set Head Key"));
}

void MotionPanel::deleteKey()
{
    HeadMotion motion = m_document->headMotion();
    const int row = m_keys->currentRow();
    if (row < 0 || !motion.removeKey(static_cast<std::size_t>(row)))
        return;
    apply(motion, tr("Delete Head Key"));
}

void MotionPanel::keyTimeEdited()
{
    HeadMotion motion = m_document->headMotion();
    const int row = m_keys->currentRow();
    if (row < 0 || row >= static_cast<int>(motion.keys().size()))
        return;
    // On the timeline's nearest frame, as Set Key and the head drag key: the box shows
    // milliseconds, so a time typed as shown (0.458 s for 11/24 s) must not leave the frame.
    const double seconds = snappedToFrame(m_keyTime->value(), m_document->timeline().fps);
    std::size_t newIndex = 0;
    if (const std::string refused = motion.moveKey(static_cast<std::size_t>(row), seconds, &newIndex);
        !refused.empty()) {
        emit message(QString::fromStdString(refused));
        showMotion();
        return;
    }
    if (motion == m_document->headMotion())
        return;
    apply(motion, tr("Move Head Key"));
    m_keys->setCurrentRow(static_cast<int>(newIndex));
    emit keySelected(motion.keys()[newIndex].timeSeconds); // the timeline follows the moved key
}

} // namespace wisp
