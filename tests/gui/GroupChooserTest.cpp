// The group chooser of Open Mesh: each OBJ group with its vertex count, the largest preselected.
#include <QApplication>
#include <QFile>
#include <QListWidget>
#include <QTimer>
#include <QtTest>

#include "ModelTestFixtures.h"
#include "boneless/Correspondence.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/GroupChooser.h"
#include "boneless/ui/MainWindow.h"

using namespace boneless;
using namespace boneless::ui;

namespace {

// A strip of `quads` unit quads over its own vertices, as OBJ lines after `base` earlier vertices.
QString strip(const QString& group, int quads, int base) {
    QString text = "g " + group + "\n";
    for (int i = 0; i <= quads; ++i) text += QString("v %1 0 0\nv %1 1 0\n").arg(i);
    for (int i = 0; i < quads; ++i) {
        const int a = base + 2 * i + 1;
        text += QString("f %1 %2 %3 %4\n").arg(a).arg(a + 2).arg(a + 3).arg(a + 1);
    }
    return text;
}

}  // namespace

class GroupChooserTest : public QObject {
    Q_OBJECT
    QString path_;

  private slots:
    void initTestCase() {
        test::isolate("GroupChooserTest");
        path_ = test::freshFolder("GroupChooserTest") + "/groups.obj";
        QFile file(path_);
        QVERIFY(file.open(QIODevice::WriteOnly));
        // Sizes 6, 14 and 4 vertices: the largest is neither first nor last in the file.
        file.write(
            (strip("eyebrows", 2, 0) + strip("body", 6, 6) + strip("tongue", 1, 20)).toUtf8());
    }

    void listsEachGroupWithItsVertexCountAndPreselectsTheLargest() {
        const std::vector<ObjGroup> groups = objGroups(path_.toStdString());
        QCOMPARE(groups.size(), size_t(3));
        GroupChooser chooser("groups.obj", groups);
        QListWidget* list = chooser.list();
        QCOMPARE(list->count(), 4);  // three groups and the whole file
        QCOMPARE(list->item(0)->text(), QString("body — 14 vertices"));
        QCOMPARE(list->item(1)->text(), QString("eyebrows — 6 vertices"));
        QCOMPARE(list->item(2)->text(), QString("tongue — 4 vertices"));
        QCOMPARE(chooser.group(), QString("body"));
        list->setCurrentRow(3);
        QCOMPARE(chooser.group(), QString());
        list->setCurrentRow(2);
        QCOMPARE(chooser.group(), QString("tongue"));
    }

    void theCountShownIsTheSizeOfTheMeshTheGroupOpensAs() {
        const std::vector<ObjGroup> groups = objGroups(path_.toStdString());
        for (const ObjGroup& g : groups) {
            Document d;
            QVERIFY(d.loadMesh(path_, QString::fromStdString(g.name)));
            QCOMPARE(d.mesh().vertexCount(), g.vertices);
        }
    }

    // So that a solve of the whole file can say which group the map needs.
    void aSavedMapNamesTheGroupItWasMadeOn() {
        Document d;
        QVERIFY(d.loadMesh(path_, "body"));
        const QString map = test::freshFolder("GroupChooserTest-map") + "/body.map.json";
        QVERIFY(d.saveCorrespondence(map));
        const Correspondence back = Correspondence::read(map.toStdString());
        QCOMPARE(QString::fromStdString(back.meshGroup), QString("body"));
        QCOMPARE(back.meshVertices, 14);
    }

    // Files given on the command line or dropped go through openFile, as File → Open Mesh does.
    void openingAFileByNameAlsoAsksAndOpensTheLargestGroup() {
        MainWindow window;
        bool asked = false;
        QTimer::singleShot(0, [&] {
            auto* chooser = qobject_cast<GroupChooser*>(QApplication::activeModalWidget());
            asked = chooser != nullptr;
            if (chooser) chooser->accept();
        });
        QVERIFY(window.openFile(path_));
        QVERIFY(asked);
        QCOMPARE(window.document()->mesh().vertexCount(), 14);
    }
};

QTEST_MAIN(GroupChooserTest)
#include "GroupChooserTest.moc"
