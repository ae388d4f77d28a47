// The application's numbers under a German locale: its widgets show and take them as the CLI
// and the project files write them ("10.0 mm", not "10,0 mm"), and so do core's messages.
#include <QDoubleSpinBox>
#include <QLocale>
#include <QtTest>
#include <clocale>
#include <cstdio>

#include "boneless/ui/NumberFormat.h"

class NumberFormatTest : public QObject {
    Q_OBJECT
  private slots:
    void aGermanUserSeesAndTypesNumbersWithADecimalPoint() {
        // As QApplication sets it for a user in Germany.
        const QByteArray saved = std::setlocale(LC_ALL, nullptr);
        if (!std::setlocale(LC_ALL, "de_DE.UTF-8"))
            QSKIP("the locale de_DE.UTF-8 is not generated here");
        const QLocale savedDefault;
        QLocale::setDefault(QLocale(QLocale::German, QLocale::Germany));
        const auto restore = qScopeGuard([&] {
            std::setlocale(LC_ALL, saved.constData());
            QLocale::setDefault(savedDefault);
        });

        boneless::ui::useOneNumberFormat();
        QDoubleSpinBox offset;
        offset.setDecimals(1);
        offset.setRange(-100, 100);
        offset.setValue(10);
        QCOMPARE(offset.text(), QString("10.0"));
        QCOMPARE(offset.valueFromText("12.5"), 12.5);
        QCOMPARE(QLocale().toString(12345), QString("12345"));  // counts as the CLI gives them
        char printed[16];
        std::snprintf(printed, sizeof printed, "%g", 12.5);  // core's, OpenMesh's, VTK's
        QCOMPARE(QString(printed), QString("12.5"));
    }
};

QTEST_MAIN(NumberFormatTest)
#include "NumberFormatTest.moc"
