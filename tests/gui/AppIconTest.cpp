// The application's icon reaches the main window and the About box.
#include <QAction>
#include <QMenuBar>
#include <QMessageBox>
#include <QTimer>
#include <QtTest>

#include "ViewTestSupport.h"
#include "boneless/ui/AppIcon.h"
#include "boneless/ui/MainWindow.h"

using namespace boneless::ui;

class AppIconTest : public QObject {
    Q_OBJECT
  public:
    static void initMain() { setDefaultSurfaceFormat(); }

  private slots:
    void initTestCase() { test::isolate("AppIconTest"); }

    void theIconHoldsEverySizeTheDesktopAsksFor() {
        const QIcon icon = applicationIcon();
        for (int size : {16, 32, 48, 64, 128, 256}) {
            const QPixmap pixmap = icon.pixmap(size, size);
            QCOMPARE(pixmap.size(), QSize(size, size));
            // Drawn, not blank: the corner is transparent and the middle is not.
            const QImage image = pixmap.toImage();
            QCOMPARE(qAlpha(image.pixel(0, 0)), 0);
            QVERIFY(qAlpha(image.pixel(size / 2, size / 2)) > 0);
        }
    }

    void theWindowAndTheAboutBoxShowTheApplicationIcon() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        const QImage expected = applicationIcon().pixmap(64, 64).toImage();
        QCOMPARE(window.windowIcon().pixmap(64, 64).toImage(), expected);

        QAction* about = nullptr;
        for (QAction* menu : window.menuBar()->actions())
            if (menu->menu())
                for (QAction* a : menu->menu()->actions())
                    if (a->text().contains("About")) about = a;
        QVERIFY(about);
        QImage shown;
        QTimer::singleShot(0, [&] {
            auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
            if (!box) return;
            shown = box->iconPixmap().toImage();
            box->accept();
        });
        about->trigger();
        QVERIFY(!shown.isNull());
        const QImage scaled = applicationIcon().pixmap(shown.size()).toImage();
        QCOMPARE(shown.convertToFormat(QImage::Format_ARGB32),
                 scaled.convertToFormat(QImage::Format_ARGB32));
    }
};

QTEST_MAIN(AppIconTest)
#include "AppIconTest.moc"
