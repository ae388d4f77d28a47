// A file that will not open gets one plain sentence, with the technical cause under it.
#include <QFile>
#include <QMessageBox>
#include <QtTest>

#include "ViewTestSupport.h"
#include "boneless/ui/MainWindow.h"

using namespace boneless::ui;

class ErrorTextTest : public QObject {
    Q_OBJECT
  public:
    static void initMain() { setDefaultSurfaceFormat(); }

  private slots:
    void initTestCase() {
        test::isolate("ErrorTextTest");
        folder_ = test::freshFolder("ErrorTextTest");
        project_ = test::writeDemoProject(folder_ + "/demo");
    }

    void aBadFileGetsAPlainSentenceAndTheDetailUnderIt() {
        QFile good(folder_ + "/demo/walker.c3d");
        QVERIFY(good.open(QIODevice::ReadOnly));
        const QByteArray take = good.readAll();
        const std::pair<QString, QByteArray> files[] = {
            {"garbage.c3d", QByteArray(3000, 'u')},
            {"cut.c3d", take.left(600)},
            {"garbage.obj", QByteArray("v 1 2\nf 1 2 x\n")}};
        const QString sentences[] = {"garbage.c3d is not a C3D file.",
                                     "cut.c3d is a C3D file that Boneless could not read.",
                                     "garbage.obj could not be opened as a mesh."};
        MainWindow window;
        QVERIFY(window.openProject(project_));
        for (int i = 0; i < 3; ++i) {
            const QString path = folder_ + "/" + files[i].first;
            QFile f(path);
            QVERIFY(f.open(QIODevice::WriteOnly));
            f.write(files[i].second);
            f.close();
            QVERIFY(!window.openFile(path));
            const auto boxes = window.findChildren<QMessageBox*>("errorMessage");
            QVERIFY(!boxes.isEmpty());
            QMessageBox* box = boxes.last();
            QCOMPARE(box->text(), sentences[i]);
            // The detail names the file and what is wrong in it, for a bug report.
            QVERIFY2(box->detailedText().size() > 10, qPrintable(box->detailedText()));
            box->close();
            QTest::qWait(0);
        }
        QVERIFY(window.document()->hasTake());  // the demo's take is still there
    }

  private:
    QString folder_, project_;
};

QTEST_MAIN(ErrorTextTest)
#include "ErrorTextTest.moc"
