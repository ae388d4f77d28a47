#include "OffsetRow.h"

#include <QAction>
#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>

#include "boneless/Correspondence.h"
#include "boneless/ui/Document.h"

namespace boneless::ui {

QLayout* makeOffsetRow(Document* document, QAction* allMapped) {
    auto* row = new QHBoxLayout;
    auto* spin = new QDoubleSpinBox;
    spin->setObjectName("offsetSpin");
    spin->setRange(Correspondence::kMinOffsetMm, Correspondence::kMaxOffsetMm);
    spin->setDecimals(1);
    spin->setSuffix(QObject::tr(" mm"));
    spin->setKeyboardTracking(false);  // one edit when the number is finished, not per digit
    spin->setToolTip(QObject::tr("How far the selected marker sits off the skin"));
    auto* all = new QPushButton(QObject::tr("All mapped"));
    all->setObjectName("offsetAll");
    all->setToolTip(QObject::tr("Give every mapped marker this offset off the skin"));
    all->setAutoDefault(true);  // Enter presses it when focused, as Space does
    auto* label = new QLabel(QObject::tr("Offset off the skin"));
    label->setBuddy(spin);  // the spin box's name, for a screen reader
    row->addWidget(label);
    row->addWidget(spin, 1);
    row->addWidget(all);

    auto show = [=] {
        const int marker = document->selectedMarker();
        const bool mapped = marker >= 0 && document->mappedVertex(marker) >= 0;
        const QSignalBlocker quiet(spin);
        spin->setEnabled(mapped && !document->editsHeld());
        if (mapped) spin->setValue(document->markerOffsetMm(marker));
        allMapped->setEnabled(document->mappedCount() > 0 && !document->editsHeld());
    };
    QObject::connect(document, &Document::selectionChanged, spin, show);
    QObject::connect(document, &Document::correspondenceChanged, spin, show);
    QObject::connect(document, &Document::editsHeldChanged, spin, show);
    QObject::connect(spin, &QDoubleSpinBox::valueChanged, document, [=](double mm) {
        if (document->selectedMarker() >= 0)
            document->setOffsetMm({document->selectedMarker()}, mm);
    });
    QObject::connect(allMapped, &QAction::enabledChanged, all, &QWidget::setEnabled);
    QObject::connect(all, &QPushButton::clicked, allMapped, &QAction::trigger);
    QObject::connect(allMapped, &QAction::triggered, document, [=] {
        std::vector<int> mapped;
        for (int m = 0; m < document->markerCount(); ++m)
            if (document->mappedVertex(m) >= 0) mapped.push_back(m);
        document->setOffsetMm(mapped, spin->value());
    });
    show();
    all->setEnabled(allMapped->isEnabled());
    return row;
}

}  // namespace boneless::ui
