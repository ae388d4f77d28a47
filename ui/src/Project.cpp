#include "boneless/ui/Project.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QSaveFile>
#include <cmath>

#include "boneless/Correspondence.h"
#include "boneless/ui/Document.h"

namespace boneless::ui::Project {

namespace {

const char* kFormat = "boneless-project";
constexpr int kVersion = 1;

QString relativeTo(const QDir& dir, const QString& path) {
    return path.isEmpty() ? QString() : dir.relativeFilePath(QFileInfo(path).absoluteFilePath());
}

QString resolve(const QDir& dir, const QString& path) {
    return path.isEmpty() ? QString() : QDir::cleanPath(dir.absoluteFilePath(path));
}

QJsonObject alignmentJson(const Calibration& c) {
    const Similarity& s = c.takeToMesh;
    QJsonArray rotation;
    for (int r = 0; r < 3; ++r) rotation.append(QJsonArray{s.R(r, 0), s.R(r, 1), s.R(r, 2)});
    return {{"calibration_frame", c.frame}, {"scale", s.scale},
            {"rotation", rotation},         {"translation", QJsonArray{s.t.x(), s.t.y(), s.t.z()}},
            {"residual", c.residual},       {"visible_markers", c.visibleMarkers}};
}

// A number the solver can work with: finite and no larger than `limit` in magnitude.
bool sane(const QJsonValue& v, double limit = 1e12) {
    return v.isDouble() && std::isfinite(v.toDouble()) && std::abs(v.toDouble()) <= limit;
}

bool readAlignment(const QJsonObject& o, Calibration& c) {
    const QJsonArray rotation = o["rotation"].toArray(), t = o["translation"].toArray();
    if (rotation.size() != 3 || t.size() != 3 || !sane(o["scale"]) || o["scale"].toDouble() <= 0)
        return false;
    for (int r = 0; r < 3; ++r) {
        const QJsonArray row = rotation[r].toArray();
        if (row.size() != 3) return false;
        for (int k = 0; k < 3; ++k) {
            if (!sane(row[k], 2.0)) return false;
            c.takeToMesh.R(r, k) = row[k].toDouble();
        }
    }
    for (int k = 0; k < 3; ++k)
        if (!sane(t[k])) return false;
    // A rotation, not any matrix: a hostile one would shear the take out of shape.
    if (!(c.takeToMesh.R * c.takeToMesh.R.transpose()).isIdentity(1e-3)) return false;
    c.takeToMesh.scale = o["scale"].toDouble();
    c.takeToMesh.t = Vec3(t[0].toDouble(), t[1].toDouble(), t[2].toDouble());
    c.frame = o["calibration_frame"].toInt(-1);
    c.residual = o["residual"].toDouble();
    c.visibleMarkers = o["visible_markers"].toInt();
    return true;
}

// rigidity_weight, orientation_weight and max_iterations tune the exact method only; they are
// written whatever the method, so that switching back to it finds them as they were.
QJsonObject settingsJson(const TakeSolveOptions& o) {
    return {{"marker_weight", o.markerWeight},
            {"low_pass_hz", o.lowPassHz},
            {"fill_gaps_s", o.fillGapSeconds},
            {"calibration_frame", o.calibrationFrame},
            {"calibrate", calibrateModeName(o.calibrate)},
            {"rigidity_weight", o.solver.rigidityWeight},
            {"orientation_weight", o.solver.orientationWeight},
            {"max_iterations", o.solver.maxIterations},
            {"method", methodName(o.solver.method)}};
}

// Each setting, when present, must be a number in the range the solver accepts; the name of the
// first that is not goes to *bad.
bool checkSettings(const QJsonObject& o, QString* bad) {
    const struct {
        const char* key;
        double low, high;
    } ranges[] = {{"marker_weight", 1e-9, 1e9}, {"low_pass_hz", 0, 1e5},
                  {"fill_gaps_s", 0, 3600},     {"calibration_frame", -1, 1e9},
                  {"rigidity_weight", 0, 1e9},  {"orientation_weight", 0, 1e9},
                  {"max_iterations", 1, 1e4}};
    for (const auto& r : ranges) {
        const QJsonValue v = o[r.key];
        if (v.isUndefined()) continue;
        if (!sane(v) || v.toDouble() < r.low || v.toDouble() > r.high) {
            *bad = r.key;
            return false;
        }
    }
    return true;
}

TakeSolveOptions readSettings(const QJsonObject& o) {
    TakeSolveOptions s;  // absent keys keep their defaults, so older projects still load
    s.markerWeight = o["marker_weight"].toDouble(s.markerWeight);
    s.lowPassHz = o["low_pass_hz"].toDouble(s.lowPassHz);
    s.fillGapSeconds = o["fill_gaps_s"].toDouble(s.fillGapSeconds);
    s.calibrationFrame = o["calibration_frame"].toInt(s.calibrationFrame);
    // Projects from before calibration have no "calibrate": they calibrate, as solve does now.
    CalibrateMode calibrate = s.calibrate;
    if (parseCalibrateMode(o["calibrate"].toString().toStdString(), calibrate))
        s.calibrate = calibrate;
    s.solver.rigidityWeight = o["rigidity_weight"].toDouble(s.solver.rigidityWeight);
    s.solver.orientationWeight = o["orientation_weight"].toDouble(s.solver.orientationWeight);
    s.solver.maxIterations = o["max_iterations"].toInt(s.solver.maxIterations);
    // "exact" only when asked for by name. Older projects say "direct" (the default then, never
    // a user's choice) or "iterative", methods that are gone: they solve local/global. Their
    // "continuation_steps" and "coarsest_leads" tuned those methods and are ignored.
    SolverOptions::Method method = SolverOptions::Method::LocalGlobal;
    if (parseMethod(o["method"].toString().toStdString(), method)) s.solver.method = method;
    return s;
}

bool readEmbeddedMap(const QJsonObject& o, Correspondence& map, QString* error) {
    try {
        map =
            Correspondence::fromJson(QJsonDocument(o).toJson(QJsonDocument::Compact).toStdString(),
                                     "the project's correspondence");
    } catch (const std::exception& e) {
        if (error) *error = QString::fromStdString(e.what());
        return false;
    }
    return true;
}

}  // namespace

QByteArray toJson(const Document& document, const QString& path) {
    const QDir dir = QFileInfo(path).absoluteDir();
    QJsonObject root{{"format", kFormat}, {"version", kVersion}};
    root["mesh"] = QJsonObject{{"file", relativeTo(dir, document.meshPath())},
                               {"group", document.meshGroup()}};
    root["take"] = QJsonObject{{"file", relativeTo(dir, document.takePath())}};
    root["correspondence"] = QJsonObject{
        {"file", relativeTo(dir, document.correspondencePath())},
        {"modified", document.correspondenceModified()},
        {"map",
         QJsonDocument::fromJson(QByteArray::fromStdString(document.correspondence().toJson()))
             .object()}};
    root["alignment"] = document.alignment() ? QJsonValue(alignmentJson(*document.alignment()))
                                             : QJsonValue(QJsonValue::Null);
    root["settings"] = settingsJson(document.settings());
    root["view"] = QJsonObject::fromVariantMap(document.viewSettings());
    return QJsonDocument(root).toJson(QJsonDocument::Indented);
}

bool save(const Document& document, const QString& path, QString* error) {
    QSaveFile file(path);
    if (!file.open(QIODevice::WriteOnly) || file.write(toJson(document, path)) < 0 ||
        !file.commit()) {
        if (error)
            *error = QObject::tr("%1: cannot save the project (%2)").arg(path, file.errorString());
        return false;
    }
    return true;
}

bool load(Document& document, const QString& path, QString* error) {
    auto fail = [&](const QString& why) {
        if (error) *error = path + ": " + why;
        return false;
    };
    QFile file(path);
    if (!file.open(QIODevice::ReadOnly)) return fail(file.errorString());
    QJsonParseError parseError;
    const QJsonDocument json = QJsonDocument::fromJson(file.readAll(), &parseError);
    if (json.isNull())
        return fail(QObject::tr("not JSON (%1 at byte %2)")
                        .arg(parseError.errorString())
                        .arg(parseError.offset));
    if (!json.isObject()) return fail(QObject::tr("not a Boneless project (not a JSON object)"));
    const QJsonObject root = json.object();
    if (root["format"].toString() != kFormat)
        return fail(QObject::tr("not a Boneless project (format is not \"%1\")").arg(kFormat));
    if (root["version"].toInt() != kVersion)
        return fail(QObject::tr("project version %1 is not supported (this Boneless reads %2)")
                        .arg(root["version"].toInt())
                        .arg(kVersion));

    const QDir dir = QFileInfo(path).absoluteDir();
    Document::State state;
    QString why;
    const QJsonObject mesh = root["mesh"].toObject();
    if (const QString m = resolve(dir, mesh["file"].toString()); !m.isEmpty())
        if (!Document::readMeshFile(m, mesh["group"].toString(), state, &why)) return fail(why);
    if (const QString t = resolve(dir, root["take"].toObject()["file"].toString()); !t.isEmpty())
        if (!Document::readTakeFile(t, state, &why)) return fail(why);
    const QJsonObject correspondence = root["correspondence"].toObject();
    state.mapPath = resolve(dir, correspondence["file"].toString());
    if (correspondence["map"].isObject()) {
        if (!readEmbeddedMap(correspondence["map"].toObject(), state.map, &why)) return fail(why);
    } else if (!state.mapPath.isEmpty()) {
        try {
            state.map = Correspondence::read(state.mapPath.toStdString());
        } catch (const std::exception& e) {
            return fail(QString::fromStdString(e.what()));
        }
    }
    if (root["alignment"].isObject()) {
        Calibration c;
        if (!readAlignment(root["alignment"].toObject(), c))
            return fail(QObject::tr("the alignment is incomplete"));
        state.alignment = c;
    }
    QString bad;
    if (!checkSettings(root["settings"].toObject(), &bad))
        return fail(QObject::tr("the setting \"%1\" is not a number in its range").arg(bad));
    state.settings = readSettings(root["settings"].toObject());
    state.viewSettings = root["view"].toObject().toVariantMap();
    if (!document.restoreState(std::move(state))) return fail(document.lastError());
    return true;
}

}  // namespace boneless::ui::Project
