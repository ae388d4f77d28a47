// Mapping as a user does it: a click beside the mesh says so, and opening a correspondence file
// over mappings already made asks first (replace, merge or cancel).
#include <QMessageBox>
#include <QPushButton>
#include <QStatusBar>
#include <QtTest>

#include "ViewTestSupport.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/MainWindow.h"
#include "boneless/ui/MeshView.h"

using namespace boneless::ui;

namespace {

// Answers the next modal question by the button with this object name.
void answer(const QString& button) {
    QTimer::singleShot(200, [button] {
        auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
        QVERIFY(box);
        QCOMPARE(box->objectName(), QString("mapLoadQuestion"));
        box->findChild<QPushButton*>(button)->click();
    });
}

}  // namespace

class MappingTest : public QObject {
    Q_OBJECT
  public:
    static void initMain() { setDefaultSurfaceFormat(); }

  private slots:
    void initTestCase() {
        test::isolate("MappingTest");
        folder_ = test::freshFolder("MappingTest");
        project_ = test::writeDemoProject(folder_ + "/demo");
    }

    void aClickBesideTheMeshSaysNothingWasMapped() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openProject(project_));
        QVERIFY(test::showAndWait(window));
        Document* d = window.document();
        d->setSelectedMarker(0);
        const int before = d->mappedVertex(0);
        QTest::mouseClick(window.meshView(), Qt::LeftButton, {}, QPoint(3, 3));
        QVERIFY2(window.statusBar()->currentMessage().contains("missed the mesh"),
                 qPrintable(window.statusBar()->currentMessage()));
        QCOMPARE(d->mappedVertex(0), before);
    }

    void openingAMapOverMappingsAsksReplaceMergeOrCancel() {
        MainWindow window;
        QVERIFY(window.openProject(project_));
        QVERIFY(test::showAndWait(window));
        Document* d = window.document();
        const QString map = folder_ + "/demo/walker.map.json";
        const int all = d->markerCount();
        const int fileVertex = d->mappedVertex(1);
        // A hand-made mapping the file disagrees with, on a vertex the file does not use.
        int mine = 0;
        while (d->markerForVertex(mine) >= 0) ++mine;
        QVERIFY(d->clearMapping(0));
        QVERIFY(d->clearMapping(1));
        QVERIFY(d->assign(1, mine));

        answer("cancelButton");
        QVERIFY(!window.openFile(map));
        QCOMPARE(d->mappedCount(), all - 1);

        answer("mergeButton");
        QVERIFY(window.openFile(map));
        QCOMPARE(d->mappedCount(), all);     // marker 0 from the file
        QCOMPARE(d->mappedVertex(1), mine);  // marker 1 kept as made

        answer("replaceButton");
        QVERIFY(window.openFile(map));
        QCOMPARE(d->mappedVertex(1), fileVertex);
        QCOMPARE(d->mappedCount(), all);
    }

  private:
    QString folder_, project_;
};

QTEST_MAIN(MappingTest)
#include "MappingTest.moc"
