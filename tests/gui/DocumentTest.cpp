// Document: loading, undoable map edits, alignment, and failures that become messages.
#include <cctype>

#include <QFile>
#include <QJsonDocument>
#include <QJsonObject>
#include <QSignalSpy>
#include <QUndoStack>
#include <QtTest>

#include "ModelTestFixtures.h"
#include "boneless/C3dWriter.h"
#include "boneless/MarkerSuggestion.h"
#include "boneless/OutputFolder.h"
#include "boneless/ui/FrameSolver.h"
#include "boneless/ui/MarkerListModel.h"

using namespace boneless;
using namespace boneless::ui;

namespace {

// The vertex `map` gives the document's marker row (labels resolve through the take, as in core).
int vertexInMap(const Document& d, const Correspondence& map, int marker) {
    for (const auto& m : map.markers)
        if (d.take().findPoint(m.label) == std::size_t(d.markerPoint(marker))) return m.vertex;
    return -1;
}

// `take` with a second subject ("second") wearing the marker at point `worn` too, moving as it
// does, written to `path`; the point added.
C3dPoint writeWithASecondSubject(C3dTake take, std::size_t worn, const QString& path) {
    C3dPoint second = take.points[worn];
    second.subject = "second";
    second.label = "second:" + second.name;
    take.points.push_back(second);
    C3dSamples samples(take.samples.frames(), take.points.size());
    for (std::size_t f = 0; f < samples.frames(); ++f)
        for (std::size_t p = 0; p < take.points.size(); ++p)
            if (const auto x = take.samples.position(f, p + 1 < take.points.size() ? p : worn))
                samples.set(f, p, x->x(), x->y(), x->z());
    take.samples = samples;
    writeC3d(take, path.toStdString());
    return second;
}

}  // namespace

class DocumentTest : public QObject {
    Q_OBJECT
    QString work_, demo_;

  private slots:
    void initTestCase() {
        test::isolate("DocumentTest");
        work_ = test::freshFolder("DocumentTest");
        demo_ = work_ + "/demo";
        test::writeDemoProject(demo_);
    }

    void loadsTheDemo() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        QVERIFY(d.hasMesh());
        QVERIFY(d.hasTake());
        QCOMPARE(d.markerCount(), 39);
        QCOMPARE(d.mappedCount(), 39);
        QCOMPARE(d.frameCount(), 60);
        QVERIFY(d.frameRate() > 0);
        QVERIFY(!d.correspondenceModified());
        QString why;
        QVERIFY2(d.canSolve(&why), qPrintable(why));
        QVERIFY(!d.alignment());
        // Every mapped vertex leads back to its marker.
        for (int m = 0; m < d.markerCount(); ++m) QCOMPARE(d.markerForVertex(d.mappedVertex(m)), m);
    }

    void markersAreDrawnNextToTheirVertices() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        const Calibration c = d.displayAlignment();
        const Positions P = d.markerPositions(c.frame);
        const double diagonal = boundingBoxDiagonal(d.mesh().V);
        int near = 0;
        for (int m = 0; m < d.markerCount(); ++m) {
            if (!P.row(m).allFinite()) continue;
            const double distance = (P.row(m) - d.mesh().V.row(d.mappedVertex(m))).norm();
            near += distance < 0.05 * diagonal;
        }
        // At the calibration frame the take is closest to the rest pose.
        QVERIFY2(near >= 25, qPrintable(QString::number(near)));
    }

    void beforeThreeAreMappedTheTakeStandsUpOnTheMesh() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        for (int m = 0; m < d.markerCount(); ++m) d.clearMapping(m);
        const Calibration c = d.displayAlignment();
        const Positions P = d.markerPositions(c.frame);
        const Correspondence demoMap =
            Correspondence::read((demo_ + "/walker.map.json").toStdString());
        const double height =
            (d.mesh().V.colwise().maxCoeff() - d.mesh().V.colwise().minCoeff()).maxCoeff();
        // The demo's actor is its mesh walking: upright, its size and facing its way, each
        // marker lands near the vertex it belongs to.
        int near = 0;
        for (int m = 0; m < d.markerCount(); ++m) {
            const int v = vertexInMap(d, demoMap, m);
            if (v < 0 || !P.row(m).allFinite()) continue;
            near += (P.row(m) - d.mesh().V.row(v)).norm() < 0.15 * height;
        }
        QVERIFY2(near >= 35, qPrintable(QString::number(near)));  // all 39 do
    }

    // Opening a second mesh said "The marker map (0 markers) was made for another mesh and was
    // cleared": there was no map to clear. A map with markers is still cleared, and said so.
    void aSecondMeshClearsNoEmptyMapAndSaysSoOfAFullOne() {
        const QString tetra = work_ + "/tetra.obj";
        QFile f(tetra);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
        f.close();
        Document d;
        QVERIFY(d.loadMesh(tetra));
        QVERIFY(d.loadMesh(demo_ + "/walker.obj"));
        QVERIFY2(!d.meshWarnings().join("\n").contains("was cleared"),
                 qPrintable(d.meshWarnings().join("\n")));
        QVERIFY(test::loadDemo(d, demo_));
        QVERIFY(d.loadMesh(tetra));
        QVERIFY2(d.meshWarnings().join("\n").contains(
                     "The marker map (39 markers) was made for another mesh and was cleared."),
                 qPrintable(d.meshWarnings().join("\n")));
    }

    void missingFilesAndCorruptTakesAreMessages() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        QSignalSpy errors(&d, &Document::errorOccurred);

        QVERIFY(!d.loadMesh(work_ + "/nope.obj"));
        QCOMPARE(errors.count(), 1);
        QVERIFY(errors.last().at(0).toString().contains("nope.obj"));

        const QString corrupt = work_ + "/corrupt.c3d";
        QFile take(demo_ + "/walker.c3d");
        QVERIFY(take.open(QIODevice::ReadOnly));
        QByteArray bytes = take.readAll().left(700);  // header and parameters cut short
        QFile out(corrupt);
        QVERIFY(out.open(QIODevice::WriteOnly));
        out.write(bytes);
        out.close();
        QVERIFY(!d.loadTake(corrupt));
        QCOMPARE(errors.count(), 2);
        QVERIFY(errors.last().at(0).toString().contains("corrupt.c3d"));

        QVERIFY(!d.loadCorrespondence(work_ + "/corrupt.c3d"));  // not JSON
        QCOMPARE(errors.count(), 3);

        // Nothing of the session was lost.
        QCOMPARE(d.frameCount(), 60);
        QCOMPARE(d.mappedCount(), 39);
        QVERIFY(d.canSolve());
    }

    // A map's face points were checked against the vertex count alone: an entry on a face the
    // mesh lacks, or on a face its vertex is not a corner of (faces triangulated otherwise since),
    // was taken, and every frame then failed as "could not be solved". Refused when opened,
    // naming the marker, as `solve` refuses it; the map in use stays.
    void aMapWhoseFacePointDoesNotFitTheMeshIsRefusedWhenOpened() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        QSignalSpy errors(&d, &Document::errorOccurred);
        Correspondence map = Correspondence::read((demo_ + "/walker.map.json").toStdString());
        MarkerMapping& m = map.markers[0];
        int other = 0;  // a face that does not have m's vertex as a corner
        while ((d.mesh().F.row(other).array() == m.vertex).any()) ++other;
        m.face = other;
        m.barycentric = {0.2, 0.3, 0.5};
        const QString notACorner = work_ + "/not-a-corner.map.json";
        map.write(notACorner.toStdString());
        QVERIFY(!d.loadCorrespondence(notACorner));
        QCOMPARE(errors.count(), 1);
        const QString said = errors.last().at(0).toString();
        QVERIFY2(said.contains("not-a-corner.map.json") &&
                     said.contains("marker " + QString::fromStdString(m.label) + ": vertex " +
                                   QString::number(m.vertex) + " is not a corner of face " +
                                   QString::number(other)),
                 qPrintable(said));
        m.face = int(d.mesh().F.rows());
        const QString past = work_ + "/past.map.json";
        map.write(past.toStdString());
        QVERIFY(!d.loadCorrespondence(past));
        QVERIFY2(errors.last().at(0).toString().contains("is out of range"),
                 qPrintable(errors.last().at(0).toString()));
        QCOMPARE(d.mappedCount(), 39);
        QVERIFY(d.canSolve());
    }

    // The first marker mapped by clicking took offset 0 (the median of none), and so every later
    // one too: a reviewer's 7 clicks and 34 suggestions all said 0, where markers sit 10 to 15 mm
    // off the skin. The first takes 10 mm; the next the median of those mapped.
    void theFirstMarkerMappedSitsOffTheSkin() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        QVERIFY(d.clearAllMappings());
        QVERIFY(d.assign(0, 0));
        QCOMPARE(d.correspondence().markers.size(), std::size_t(1));
        QCOMPARE(d.correspondence().markers[0].offsetMm, Document::kFirstOffsetMm);
        QCOMPARE(Document::kFirstOffsetMm, 10.0);
        QVERIFY(d.setOffsetMm({0}, 14));
        QVERIFY(d.assign(1, 1));
        QCOMPARE(d.correspondence().markers[1].offsetMm, 14.0);
    }

    // Merge (Keep Mine) kept suggestions still marked for review as if they were the user's, so a
    // known-good map merged over them added nothing. Its mappings replace those; a hand-made
    // mapping stays.
    void aMergeReplacesSuggestionsStillToReviewButKeepsTheUsersOwn() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        const Correspondence good =
            Correspondence::read((demo_ + "/walker.map.json").toStdString());
        Correspondence guessed = good;
        const int vertices = d.mesh().vertexCount();
        for (MarkerMapping& m : guessed.markers) {
            m.vertex = (m.vertex + vertices / 2) % vertices;
            m.extraJson = R"({"suggested": true, "needs_review": true, "review_reason": "far"})";
        }
        guessed.markers[0].extraJson = "{}";  // mapped by hand
        const QString guesses = work_ + "/guessed.map.json";
        guessed.write(guesses.toStdString());
        QVERIFY(d.loadCorrespondence(guesses));
        const int all = int(good.markers.size());

        int added = -1, replaced = -1;
        QVERIFY(d.loadCorrespondence(work_ + "/demo/walker.map.json", Document::MapLoad::Merge,
                                     &added, &replaced));
        QCOMPARE(added, 0);
        QCOMPARE(replaced, all - 1);
        QCOMPARE(d.mappedCount(), all);
        QCOMPARE(d.correspondence().markers.size(), std::size_t(all));
        for (const MarkerMapping& m : d.correspondence().markers) {
            const auto& expected =
                m.label == guessed.markers[0].label
                    ? guessed.markers[0]
                    : *std::find_if(good.markers.begin(), good.markers.end(),
                                    [&](const MarkerMapping& g) { return g.label == m.label; });
            QCOMPARE(m.vertex, expected.vertex);
        }
        QCOMPARE(d.undoStack()->undoText(), QString("Merge Correspondence"));
    }

    void assignUndoRedo() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        QSignalSpy changes(&d, &Document::correspondenceChanged);
        const int m = 3;
        const int before = d.mappedVertex(m);
        QVERIFY(d.clearMapping(m));
        QCOMPARE(d.mappedVertex(m), -1);
        QCOMPARE(d.markerForVertex(before), -1);
        QVERIFY(d.correspondenceModified());

        int free = 0;
        while (d.markerForVertex(free) >= 0) ++free;
        QVERIFY(d.assign(m, free));
        QCOMPARE(d.mappedVertex(m), free);
        QCOMPARE(d.markerForVertex(free), m);
        QCOMPARE(d.undoStack()->count(), 2);

        d.undoStack()->undo();
        QCOMPARE(d.mappedVertex(m), -1);
        d.undoStack()->undo();
        QCOMPARE(d.mappedVertex(m), before);
        QVERIFY(!d.correspondenceModified());  // back to the file's content
        d.undoStack()->redo();
        d.undoStack()->redo();
        QCOMPARE(d.mappedVertex(m), free);
        QCOMPARE(changes.count(), 6);
        // The map written out is the edited one.
        QCOMPARE(vertexInMap(d, d.correspondence(), m), free);
    }

    void aVertexCarriesOneMarker() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        QSignalSpy errors(&d, &Document::errorOccurred);
        const int taken = d.mappedVertex(0);
        QVERIFY(!d.assign(1, taken));
        QCOMPARE(errors.count(), 1);
        QVERIFY(errors.last().at(0).toString().contains(d.markerLabel(0)));
        QCOMPARE(d.mappedVertex(0), taken);
        QCOMPARE(d.undoStack()->count(), 0);
        QVERIFY(!d.assign(0, d.mesh().vertexCount()));  // out of range
        QVERIFY(!d.assign(-1, 0));                      // no marker
    }

    void mergingAMapWhoseLabelsDifferOnlyInCaseKeepsTheMarkersMappedAlready() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        const int all = d.mappedCount();
        // The same map with its labels lower-cased, which the take still resolves.
        Correspondence lower = d.correspondence();
        for (auto& m : lower.markers)
            for (char& c : m.label) c = char(std::tolower(static_cast<unsigned char>(c)));
        const QString path = demo_ + "/lower.map.json";
        lower.write(path.toStdString());
        // Marker 0 unmapped, marker 1 mapped by hand where the file does not put it.
        int mine = 0;
        while (d.markerForVertex(mine) >= 0) ++mine;
        const int fileVertex = d.mappedVertex(1);
        QVERIFY(d.clearMapping(0));
        QVERIFY(d.clearMapping(1));
        QVERIFY(d.assign(1, mine));
        QVERIFY2(d.loadCorrespondence(path, Document::MapLoad::Merge), qPrintable(d.lastError()));
        QCOMPARE(d.undoStack()->undoText(), QString("Merge Correspondence"));
        QCOMPARE(d.mappedVertex(1), mine);  // not overridden by "its" entry in the file
        QVERIFY(d.mappedVertex(0) >= 0);    // the unmapped one taken from the file
        QCOMPARE(d.mappedCount(), all);
        QCOMPARE(int(d.correspondence().markers.size()), all);
        QVERIFY(fileVertex != mine);
    }

    // Suggest Rest left the project's mesh up out where `map suggest --mesh-up` passes it: its
    // fits were made level by the axis the alignment came nearest, not the project's. (The
    // vertices it proposes do not depend on it: the fits are turned rigidly, and so are the
    // markers they are compared with.)
    void suggestReadsTheProjectsMeshUp() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        for (int m = 0; m < d.markerCount(); ++m) {
            bool kept = false;
            for (const char* label : {"RFHD", "LWRA", "RANK", "LASI"})
                kept |= d.markerLabel(m).endsWith(label);
            if (!kept) QVERIFY(d.clearMapping(m));
        }
        TakeSolveOptions settings = d.settings();
        settings.meshUp = Vec3(1, 0, 0);  // the demo's walker stands along +y
        d.setSettings(settings);
        const Document::SuggestInputs read = d.suggestInputs();
        const Suggestion s = Document::suggest(read);
        const Suggestion levelled =
            suggestMappings(d.mesh(), d.take(), d.correspondence(), Vec3(1, 0, 0));
        const Suggestion guessed = suggestMappings(d.mesh(), d.take(), d.correspondence());
        // Were the axis of no consequence to the alignment, this test could not fail.
        QVERIFY(!levelled.calibration.takeToMesh.R.isApprox(guessed.calibration.takeToMesh.R));
        QVERIFY(s.calibration.takeToMesh.R.isApprox(levelled.calibration.takeToMesh.R));
        QVERIFY(s.suggested > 30);
        QVERIFY(read.meshUp == settings.meshUp);
    }

    void alignIsAnUndoableEditTheSolverUses() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        QSignalSpy aligned(&d, &Document::alignmentChanged);
        QVERIFY2(d.align(10), qPrintable(d.lastError()));
        QVERIFY(d.alignment());
        QCOMPARE(d.alignment()->frame, 10);
        QCOMPARE(aligned.count(), 1);
        const TakeSolveOptions o = d.solveOptions();
        QVERIFY(o.alignment);
        QCOMPARE(o.alignment->scale, d.alignment()->takeToMesh.scale);
        QVERIFY(!d.settings().alignment);
        d.undoStack()->undo();
        QVERIFY(!d.alignment());
        QVERIFY(!d.solveOptions().alignment);
        QCOMPARE(aligned.count(), 2);
    }

    void exportRequestNamesTheFilesLikeTheCli() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        ExportRequest r = d.exportRequest(work_ + "/out", ExportFormat::Pc2);
        QCOMPARE(QString::fromStdString(r.mapPath), d.correspondencePath());
        QCOMPARE(QString::fromStdString(r.c3dPath), d.takePath());
        QCOMPARE(QString::fromStdString(exportStem(r)), QString("walker"));
        QVERIFY(d.clearMapping(0));
        r = d.exportRequest(work_ + "/out", ExportFormat::Pc2);
        QVERIFY(r.mapPath.empty());  // unsaved edits: the sidecar holds the map itself
        const QString saved = work_ + "/saved.map.json";
        QVERIFY(d.saveCorrespondence(saved));
        QVERIFY(!d.correspondenceModified());
        QCOMPARE(d.correspondencePath(), saved);
        QCOMPARE(Correspondence::read(saved.toStdString()).markers.size(), std::size_t(38));
        // Undo and redo across the save bring back the demo's map file with the edit: the demo's
        // file does not hold it, so the export must not cite that file for it.
        d.undoStack()->undo();
        QVERIFY(d.correspondenceModified());
        d.undoStack()->redo();
        QCOMPARE(d.mappedCount(), 38);
        QVERIFY(d.correspondenceModified());
        QVERIFY(d.exportRequest(work_ + "/out", ExportFormat::Pc2).mapPath.empty());
    }

    // A map that names no mesh (written by hand, or by another tool) gets this mesh's name when
    // edited; opening it is no edit, so closing the window asked to save a map nobody changed.
    void aMapNamingNoMeshOpensUnedited() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        QFile demoMap(d.correspondencePath());
        QVERIFY(demoMap.open(QIODevice::ReadOnly));
        QJsonObject json = QJsonDocument::fromJson(demoMap.readAll()).object();
        QVERIFY(json.contains("mesh"));
        json.remove("mesh");
        const QString path = work_ + "/no-mesh.map.json";
        QFile noMesh(path);
        QVERIFY(noMesh.open(QIODevice::WriteOnly));
        noMesh.write(QJsonDocument(json).toJson());
        noMesh.close();
        QVERIFY(d.loadCorrespondence(path));
        QVERIFY(!d.correspondenceModified());
        QVERIFY(d.clearMapping(0));
        QVERIFY(d.correspondenceModified());

        // The same of a project whose map file names no mesh.
        const QString project = test::writeDemoProject(work_ + "/no-mesh-project");
        Document e;
        QString error;
        QVERIFY2(Project::load(e, project, &error), qPrintable(error));
        QFile projectMap(e.correspondencePath());
        QVERIFY(projectMap.open(QIODevice::WriteOnly | QIODevice::Truncate));
        projectMap.write(QJsonDocument(json).toJson());
        projectMap.close();
        Document f;
        QVERIFY2(Project::load(f, project, &error), qPrintable(error));
        QVERIFY(!f.correspondenceModified());
    }

    void selectionIsShared() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        QSignalSpy selected(&d, &Document::selectionChanged);
        d.setSelectedMarker(7);
        d.setSelectedMarker(7);
        QCOMPARE(selected.count(), 1);
        QCOMPARE(d.selectedMarker(), 7);
        d.setSelectedMarker(999);
        QCOMPARE(d.selectedMarker(), -1);
        QCOMPARE(d.markerByLabel(d.markerLabel(4).toLower()), 4);
    }

    void markersShowByTheirNameWithoutTheSubject() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        for (int m = 0; m < d.markerCount(); ++m) {
            const C3dPoint& point = d.take().points[d.markerPoint(m)];
            QVERIFY(!point.subject.empty());
            QCOMPARE(d.markerLabel(m), QString::fromStdString(point.name));
            QCOMPARE(d.markerByLabel(QString::fromStdString(point.label)), m);
        }
        // A second actor wearing one of the same markers: the bare name finds neither, so both
        // show their full labels; every other marker keeps its bare name.
        const C3dTake one = d.take();
        const std::size_t shared = d.markerPoint(0), alone = d.markerPoint(1);
        const QString path = work_ + "/two-actors.c3d";
        const C3dPoint second = writeWithASecondSubject(one, shared, path);
        QVERIFY(d.loadTake(path));
        QStringList labels;
        for (int m = 0; m < d.markerCount(); ++m) labels << d.markerLabel(m);
        for (const std::string& label :
             {one.points[shared].label, second.label, one.points[alone].name})
            QVERIFY2(labels.contains(QString::fromStdString(label)), qPrintable(labels.join(' ')));
    }

    // A bare map label two subjects of the take wear (walker:X and second:X, the map's X): the
    // solve check called it a marker the take does not have, where core refuses it for wanting
    // the subject prefix. The check now says it in core's words, in its reason and its details.
    void aBareLabelTwoSubjectsWearIsRefusedInCoresWordsNotCalledMissing() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        const QString path = work_ + "/two-subjects.c3d";
        const C3dPoint second = writeWithASecondSubject(d.take(), d.markerPoint(0), path);
        QVERIFY(d.loadTake(path));  // the demo's map stays, naming the marker without a subject
        QVERIFY(d.correspondence().find(second.name));

        // What core says when the solve resolves this map.
        std::string core;
        try {
            d.correspondence().resolve(d.take());
        } catch (const std::exception& e) {
            core = e.what();
        }
        QVERIFY2(core.find("is worn by more than one subject") != std::string::npos, core.c_str());

        QString why, detail;
        QVERIFY(!d.canSolve(&why, &detail));
        QVERIFY2(!why.contains("does not have") && !detail.contains("Not in the take"),
                 qPrintable(why + " | " + detail));
        const QString expected = QString(
                                     "marker %1 is worn by more than one subject in %2 "
                                     "(walker:%1, second:%1); write the subject prefix")
                                     .arg(QString::fromStdString(second.name), path);
        QCOMPARE(why, expected + ".");
        QCOMPARE(detail, expected + ".");
        QVERIFY2(QString::fromStdString(core).endsWith(expected), core.c_str());
    }

    // Two points of a take with one full label (Male:LFWT twice): either row could be
    // click-mapped, its entry never resolved, and the solve check called the label missing from
    // the take. Core's words say the label is shared, mapping such a row is refused with them, and
    // the marker list's tooltip says so.
    void aLabelTwoPointsOfTheTakeShareIsSaidSoAndItsRowsCannotBeMapped() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        C3dTake twice = d.take();
        const int first = d.markerPoint(2), second = d.markerPoint(5);
        twice.points[second].label = twice.points[first].label;
        twice.points[second].name = twice.points[first].name;
        const QString path = work_ + "/twice.c3d";
        writeC3d(twice, path.toStdString());
        QVERIFY(d.loadTake(path));  // the demo's map stays, naming the shared label
        const QString shared = QString::fromStdString(
            twice.sharedLabelText({std::size_t(first), std::size_t(second)}));
        QVERIFY2(shared.contains("both labelled"), qPrintable(shared));

        QString why, detail;
        QVERIFY(!d.canSolve(&why, &detail));
        QVERIFY2(why.contains(shared) && !why.contains("does not have"), qPrintable(why));
        QVERIFY2(detail.contains(shared), qPrintable(detail));

        int rowFirst = -1, rowSecond = -1, other = -1;
        for (int m = 0; m < d.markerCount(); ++m) {
            if (d.markerPoint(m) == first) rowFirst = m;
            if (d.markerPoint(m) == second) rowSecond = m;
            if (d.markerPoint(m) != first && d.markerPoint(m) != second) other = m;
        }
        QVERIFY(rowFirst >= 0 && rowSecond >= 0 && other >= 0);
        QVERIFY(d.clearAllMappings());
        for (int row : {rowFirst, rowSecond}) {
            QVERIFY(!d.assign(row, 0));
            QVERIFY2(d.lastError().contains("cannot be mapped: in twice.c3d, " + shared),
                     qPrintable(d.lastError()));
            QVERIFY(d.correspondence().markers.empty());
        }
        QVERIFY(d.assign(other, 0));

        MarkerListModel model(&d);
        const QString tip =
            model.index(rowFirst, MarkerListModel::LabelColumn).data(Qt::ToolTipRole).toString();
        QVERIFY2(tip.contains(shared), qPrintable(tip));
        QVERIFY(model.index(other, MarkerListModel::LabelColumn)
                    .data(Qt::ToolTipRole)
                    .toString()
                    .isEmpty());
    }

    void aSuggestionToReviewIsMarkedInTheMarkerList() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        MarkerListModel model(&d);
        // A map whose entry for marker 3 came from "suggest" with a reason to check it.
        Correspondence map = d.correspondence();
        const QString label = d.markerLabel(3);
        MarkerMapping* entry = nullptr;
        for (auto& m : map.markers)
            if (label.endsWith(QString::fromStdString(m.label))) entry = &m;
        QVERIFY(entry);
        entry->extraJson =
            "{\"suggested\": true, \"needs_review\": true, "
            "\"review_reason\": \"named left, but lands on the right\"}";
        const QString path = demo_ + "/review.map.json";
        map.write(path.toStdString());
        QVERIFY2(d.loadCorrespondence(path), qPrintable(d.lastError()));
        // Undo names it as File → Open Correspondence… does ("Load correspondence" before).
        QCOMPARE(d.undoStack()->undoText(), QString("Open Correspondence"));
        const QModelIndex vertex = model.index(3, MarkerListModel::VertexColumn);
        QVERIFY(vertex.data().toString().contains("check"));
        QVERIFY(
            vertex.data(Qt::ToolTipRole).toString().contains("named left, but lands on the right"));
        QVERIFY(!model.index(4, MarkerListModel::VertexColumn).data().toString().contains("check"));
        // The list's "To check" shows it alone.
        MarkerFilterProxy toCheck;
        toCheck.setSourceModel(&model);
        toCheck.setState(MarkerFilterProxy::State::ToCheck);
        QCOMPARE(toCheck.rowCount(), 1);
        QCOMPARE(toCheck.markerAt(0), 3);
        // Mapping it by hand makes it the user's: no mark left.
        int free = 0;
        while (d.markerForVertex(free) >= 0) ++free;
        QVERIFY(d.assign(3, free));
        QVERIFY(d.markerReviewReason(3).isEmpty());
        QVERIFY(!model.index(3, MarkerListModel::VertexColumn).data().toString().contains("check"));
        QCOMPARE(toCheck.rowCount(), 0);
    }

    void markerListAndFilter() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        MarkerListModel model(&d);
        MarkerFilterProxy proxy;
        proxy.setSourceModel(&model);
        QCOMPARE(model.rowCount(), 39);
        QCOMPARE(model.columnCount(), int(MarkerListModel::ColumnCount));

        // A frame where some marker is missing, and one where it is seen.
        int missingFrame = -1, hidden = -1;
        for (int f = 0; f < d.frameCount() && hidden < 0; ++f)
            for (int m = 0; m < d.markerCount() && hidden < 0; ++m)
                if (!d.markerVisible(m, f)) missingFrame = f, hidden = m;
        QVERIFY(hidden >= 0);
        int seenFrame = 0;
        while (!d.markerVisible(hidden, seenFrame)) ++seenFrame;

        model.setFrame(seenFrame);
        proxy.setState(MarkerFilterProxy::State::Missing);
        QVERIFY(proxy.rowOfMarker(hidden) < 0);
        model.setFrame(missingFrame);  // the filter follows the frame
        QVERIFY(proxy.rowOfMarker(hidden) >= 0);
        QCOMPARE(proxy.markerAt(proxy.rowOfMarker(hidden)), hidden);
        QCOMPARE(model.index(hidden, MarkerListModel::VisibleColumn).data().toString(),
                 QString("missing"));

        proxy.setState(MarkerFilterProxy::State::Unmapped);
        QCOMPARE(proxy.rowCount(), 0);
        QVERIFY(d.clearMapping(4));
        QCOMPARE(proxy.rowCount(), 1);
        QCOMPARE(proxy.markerAt(0), 4);
        QCOMPARE(model.index(4, MarkerListModel::VertexColumn).data().toString(), QString("—"));
        d.undoStack()->undo();
        QCOMPARE(proxy.rowCount(), 0);

        proxy.setState(MarkerFilterProxy::State::All);
        const QString label = d.markerLabel(7);
        proxy.setText(label.right(3).toLower());
        QVERIFY(proxy.rowOfMarker(7) >= 0);
        QVERIFY(proxy.rowCount() < 39);

        FrameResult r;
        r.frame = 9;
        r.residualMm.assign(39, std::numeric_limits<double>::quiet_NaN());
        r.residualMm[7] = 1.234;
        model.setFrameResult(r);
        QCOMPARE(model.index(7, MarkerListModel::ResidualColumn).data().toString(),
                 QString("1.23"));
        QCOMPARE(model.index(6, MarkerListModel::ResidualColumn).data().toString(), QString());
        QCOMPARE(model.residualFrame(), 9);
        QVERIFY(model.index(7, MarkerListModel::ResidualColumn)
                    .data(Qt::ToolTipRole)
                    .toString()
                    .contains("9"));
        QVERIFY(d.assign(7, d.mappedVertex(7)));  // no change: nothing to undo
        QVERIFY(d.clearMapping(7));               // residuals belonged to the old map
        QCOMPARE(model.index(7, MarkerListModel::ResidualColumn).data().toString(), QString());
        // A marker on a point of a face: the column names its vertex, the tip says it is a point.
        int face = 0;
        while (d.markerForVertex(d.mesh().F(face, 1)) >= 0) ++face;
        const int v = d.mesh().F(face, 1);
        QVERIFY(d.assign(7, SurfacePoint{v, face, Vec3(0.2, 0.6, 0.2)}));
        const QModelIndex cell = model.index(7, MarkerListModel::VertexColumn);
        QCOMPARE(cell.data().toString(), QString::number(v));
        QVERIFY2(cell.data(Qt::ToolTipRole)
                     .toString()
                     .startsWith(QString("On a point of face %1").arg(face)),
                 qPrintable(cell.data(Qt::ToolTipRole).toString()));
        QVERIFY(d.assign(7, v));  // typed, it sits on the vertex itself
        QVERIFY(!cell.data(Qt::ToolTipRole).toString().contains("face"));
    }
};

QTEST_MAIN(DocumentTest)
#include "DocumentTest.moc"
