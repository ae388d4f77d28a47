// `boneless --project P --frame N --screenshot OUT.png` against a committed baseline picture.
// Software GL (Mesa llvmpipe, forced by run-with-display.sh) draws the same picture on every
// machine up to edge pixels, so a per-pixel tolerance and a small mismatch fraction suffice.
#include <QDir>
#include <QFileInfo>
#include <QImage>
#include <QProcess>
#include <QSet>
#include <QtTest>

#include "ViewTestSupport.h"

namespace {

constexpr int kChannelTolerance = 32;       // per colour channel, 0..255
constexpr double kMaxMismatchShare = 0.01;  // of all pixels

const QString kBaseline =
    QStringLiteral(BONELESS_SOURCE_DIR "/tests/gui/baselines/demo-frame10.png");

struct Run {
    int exitCode = -1;
    QString output;
};

Run runBoneless(const QStringList& arguments, const QString& home) {
    QProcess process;
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    // The child keeps its settings and recent files in the test's folder, not the user's.
    env.insert("XDG_CONFIG_HOME", home + "/config");
    env.insert("XDG_DATA_HOME", home + "/data");
    env.insert("XDG_CACHE_HOME", home + "/cache");
    env.insert("OPENBLAS_NUM_THREADS", "1");
    process.setProcessEnvironment(env);
    process.setProcessChannelMode(QProcess::MergedChannels);
    process.start(QStringLiteral(BONELESS_GUI), arguments);
    Run run;
    if (!process.waitForFinished(240000)) {
        process.kill();
        process.waitForFinished();
        run.output = "timed out\n";
    }
    run.output += QString::fromLocal8Bit(process.readAll());
    run.exitCode = process.exitStatus() == QProcess::NormalExit ? process.exitCode() : -1;
    return run;
}

int channelDistance(QRgb a, QRgb b) {
    return std::max({std::abs(qRed(a) - qRed(b)), std::abs(qGreen(a) - qGreen(b)),
                     std::abs(qBlue(a) - qBlue(b))});
}

}  // namespace

class ScreenshotTest : public QObject {
    Q_OBJECT
  private slots:
    void initTestCase() {
        boneless::ui::test::isolate("ScreenshotTest");
        folder_ = boneless::ui::test::freshFolder("ScreenshotTest");
        project_ = boneless::ui::test::writeDemoProject(folder_ + "/demo");
    }

    void demoFrameMatchesBaseline() {
        const QString out = folder_ + "/demo-frame10.png";
        const Run run =
            runBoneless({"--project", project_, "--frame", "10", "--screenshot", out}, folder_);
        QVERIFY2(run.exitCode == 0, qPrintable(run.output));
        qInfo("boneless: %s", qPrintable(run.output.trimmed()));
        const QImage actual = QImage(out).convertToFormat(QImage::Format_RGB32);
        QVERIFY2(!actual.isNull(), qPrintable(out));
        QCOMPARE(actual.size(), QSize(800, 600));

        // Not blank: a mesh covers a good part of the background, shaded in many tones.
        const QRgb background = actual.pixel(0, 0);
        int covered = 0;
        QSet<QRgb> colours;
        for (int y = 0; y < actual.height(); ++y)
            for (int x = 0; x < actual.width(); ++x) {
                const QRgb p = actual.pixel(x, y);
                colours.insert(p);
                if (channelDistance(p, background) > kChannelTolerance) ++covered;
            }
        const double coveredShare = double(covered) / (actual.width() * actual.height());
        QVERIFY2(coveredShare > 0.05, qPrintable(QString("only %1 % of the picture differs from "
                                                         "the background")
                                                     .arg(100 * coveredShare)));
        QVERIFY2(colours.size() > 200, qPrintable(QString("%1 colours").arg(colours.size())));

        if (!QFileInfo::exists(kBaseline)) {
            QDir().mkpath(QFileInfo(kBaseline).absolutePath());
            QVERIFY(actual.save(kBaseline));
            QFAIL(qPrintable(QString("No baseline yet: wrote %1 from this run. Look at it; if it "
                                     "is right, commit it (git add %1) and run the test again.")
                                 .arg(kBaseline)));
        }
        const QImage expected = QImage(kBaseline).convertToFormat(QImage::Format_RGB32);
        QCOMPARE(expected.size(), actual.size());

        QImage diff(actual.size(), QImage::Format_RGB32);
        int mismatched = 0;
        for (int y = 0; y < actual.height(); ++y)
            for (int x = 0; x < actual.width(); ++x) {
                const QRgb a = actual.pixel(x, y), e = expected.pixel(x, y);
                const bool bad = channelDistance(a, e) > kChannelTolerance;
                mismatched += bad;
                const int grey = qGray(a) / 3;
                diff.setPixel(x, y, bad ? qRgb(255, 0, 0) : qRgb(grey, grey, grey));
            }
        const double share = double(mismatched) / (actual.width() * actual.height());
        if (share > kMaxMismatchShare) {
            const QString diffPath = folder_ + "/demo-frame10-diff.png";
            diff.save(diffPath);
            QFAIL(qPrintable(QString("%1 % of the pixels differ from the baseline %2 (allowed "
                                     "%3 %).\n  actual: %4\n  diff (red = differs): %5\nIf the "
                                     "change is intended, copy the actual picture over the "
                                     "baseline and commit it.")
                                 .arg(100 * share, 0, 'f', 2)
                                 .arg(kBaseline)
                                 .arg(100 * kMaxMismatchShare)
                                 .arg(out, diffPath)));
        }
        qInfo("%.3f %% of the pixels differ from the baseline", 100 * share);
    }

    void badProjectFailsWithMessage() {
        const QString out = folder_ + "/never.png";
        const Run run =
            runBoneless({"--project", folder_ + "/missing.boneless", "--screenshot", out}, folder_);
        QVERIFY2(run.exitCode != 0, qPrintable(run.output));
        QVERIFY2(run.output.contains("missing.boneless"), qPrintable(run.output));
        QVERIFY(!QFileInfo::exists(out));
    }

    void frameOutsideTheTakeFails() {
        const Run run = runBoneless(
            {"--project", project_, "--frame", "600", "--screenshot", folder_ + "/never.png"},
            folder_);
        QVERIFY2(run.exitCode != 0, qPrintable(run.output));
        QVERIFY2(run.output.contains("600"), qPrintable(run.output));
    }

  private:
    QString folder_, project_;
};

QTEST_MAIN(ScreenshotTest)
#include "ScreenshotTest.moc"
