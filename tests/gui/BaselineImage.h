#pragma once
// A rendered picture against a committed baseline in tests/gui/baselines/. Software GL (Mesa
// llvmpipe, forced by run-with-display.sh) draws the same picture on every machine up to edge
// pixels, so a per-pixel tolerance and a small share of mismatched pixels suffice.
//
// (Re)generating a baseline: delete it and run the test. The run writes the baseline from its
// picture and fails; look at the picture, then commit it and run the test again.

#include <QDir>
#include <QFileInfo>
#include <QImage>
#include <QString>
#include <algorithm>
#include <cstdlib>

namespace boneless::ui::test {

constexpr int kChannelTolerance = 32;  // per colour channel, 0..255

inline int channelDistance(QRgb a, QRgb b) {
    return std::max({std::abs(qRed(a) - qRed(b)), std::abs(qGreen(a) - qGreen(b)),
                     std::abs(qBlue(a) - qBlue(b))});
}

inline QString baselinePath(const QString& name) {
    return QStringLiteral(BONELESS_SOURCE_DIR "/tests/gui/baselines/") + name + ".png";
}

// Empty when `actual` matches the baseline `name` (at most `maxShare` of its pixels further than
// kChannelTolerance); else why not, with the actual picture and a diff (red = differs) saved in
// `folder` to look at. Prints the share that differs.
inline QString differenceFromBaseline(const QImage& picture, const QString& name,
                                      const QString& folder, double maxShare) {
    const QImage actual = picture.convertToFormat(QImage::Format_RGB32);
    const QString baseline = baselinePath(name);
    const QString actualPath = folder + "/" + name + ".png";
    actual.save(actualPath);
    if (!QFileInfo::exists(baseline)) {
        QDir().mkpath(QFileInfo(baseline).absolutePath());
        actual.save(baseline);
        return QString(
                   "No baseline yet: wrote %1 from this run. Look at it; if it is right, "
                   "commit it (git add %1) and run the test again.")
            .arg(baseline);
    }
    const QImage expected = QImage(baseline).convertToFormat(QImage::Format_RGB32);
    if (expected.size() != actual.size())
        return QString("the picture is %1x%2, the baseline %3 %4x%5")
            .arg(actual.width())
            .arg(actual.height())
            .arg(baseline)
            .arg(expected.width())
            .arg(expected.height());
    QImage diff(actual.size(), QImage::Format_RGB32);
    int mismatched = 0;
    for (int y = 0; y < actual.height(); ++y)
        for (int x = 0; x < actual.width(); ++x) {
            const QRgb a = actual.pixel(x, y);
            const bool bad = channelDistance(a, expected.pixel(x, y)) > kChannelTolerance;
            mismatched += bad;
            const int grey = qGray(a) / 3;
            diff.setPixel(x, y, bad ? qRgb(255, 0, 0) : qRgb(grey, grey, grey));
        }
    const double share = double(mismatched) / (actual.width() * actual.height());
    qInfo("%s: %.3f %% of the pixels differ from the baseline (allowed %.1f %%)", qPrintable(name),
          100 * share, 100 * maxShare);
    if (share <= maxShare) return {};
    const QString diffPath = folder + "/" + name + "-diff.png";
    diff.save(diffPath);
    return QString(
               "%1 % of the pixels differ from the baseline %2 (allowed %3 %).\n  actual: "
               "%4\n  diff (red = differs): %5\nIf the change is intended, copy the actual "
               "picture over the baseline and commit it.")
        .arg(100 * share, 0, 'f', 2)
        .arg(baseline)
        .arg(100 * maxShare)
        .arg(actualPath, diffPath);
}

}  // namespace boneless::ui::test
