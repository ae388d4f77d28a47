// The solved-frame cache on its own: least recently used out first, within its byte cap.
#include <QtTest>

#include "boneless/ui/FrameCache.h"

using namespace boneless::ui;

namespace {

std::shared_ptr<const FrameResult> frameOf(int frame, int vertices = 100) {
    auto r = std::make_shared<FrameResult>();
    r->frame = frame;
    r->V = boneless::Positions::Constant(vertices, 3, double(frame));
    return r;
}

}  // namespace

class FrameCacheTest : public QObject {
    Q_OBJECT
  private slots:
    void theLeastRecentlyUsedFrameGoesFirst() {
        const std::size_t one = frameOf(0)->bytes();
        FrameCache cache(3 * one);
        for (int f : {0, 1, 2}) cache.insert(frameOf(f));
        QVERIFY(cache.use(0));  // 1 is now the least recently used
        cache.insert(frameOf(3));
        QCOMPARE(cache.size(), 3);
        QVERIFY(!cache.contains(1));
        for (int f : {0, 2, 3}) QVERIFY(cache.contains(f));
        QCOMPARE(cache.bytes(), 3 * one);
        QCOMPARE(cache.use(3)->V(0, 0), 3.0);
        QVERIFY(!cache.use(1));
    }

    void aFrameSolvedAgainReplacesItsOldResult() {
        FrameCache cache(1 << 20);
        cache.insert(frameOf(4));
        auto again = std::make_shared<FrameResult>(*frameOf(4));
        again->V(0, 0) = -1;
        cache.insert(again);
        QCOMPARE(cache.size(), 1);
        QCOMPARE(cache.bytes(), again->bytes());
        QCOMPARE(cache.use(4)->V(0, 0), -1.0);
    }

    void theNewestFrameStaysEvenOverTheCap() {
        FrameCache cache(10);  // smaller than any frame
        cache.insert(frameOf(1));
        cache.insert(frameOf(2));
        QCOMPARE(cache.size(), 1);
        QVERIFY(cache.contains(2));
        QCOMPARE(cache.lastFrameBytes(), frameOf(2)->bytes());
    }

    void aLowerCapEvictsAtOnce() {
        const std::size_t one = frameOf(0)->bytes();
        FrameCache cache(4 * one);
        for (int f : {0, 1, 2, 3}) cache.insert(frameOf(f));
        cache.setLimit(2 * one);
        QCOMPARE(cache.size(), 2);
        QVERIFY(cache.contains(2) && cache.contains(3));
        cache.setLimit(0);
        QCOMPARE(cache.size(), 0);
        QCOMPARE(cache.bytes(), std::size_t(0));
    }
};

QTEST_GUILESS_MAIN(FrameCacheTest)
#include "FrameCacheTest.moc"
