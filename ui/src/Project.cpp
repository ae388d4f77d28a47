#include "boneless/ui/Project.h"

#include <algorithm>

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QSaveFile>
#include <QStringList>
#include <cmath>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string_view>

#include "boneless/Correspondence.h"
#include "boneless/InputFile.h"
#include "boneless/TakeOptionsJson.h"
#include "boneless/ui/Document.h"

namespace boneless::ui::Project {

namespace {

const char* kFormat = "boneless-project";
const char* kKind = "Boneless project";  // what notARegularFile calls such a file
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

// Empty when `o` is a whole, sound alignment (then in `c`); otherwise what is wrong with it.
QString readAlignment(const QJsonObject& o, Calibration& c) {
    const QJsonArray rotation = o["rotation"].toArray(), t = o["translation"].toArray();
    if (!sane(o["scale"]) || o["scale"].toDouble() <= 0)
        return QObject::tr("scale is not a positive number up to 1e12");
    if (t.size() != 3) return QObject::tr("translation is not three numbers");
    for (int k = 0; k < 3; ++k)
        if (!sane(t[k])) return QObject::tr("translation is not three numbers up to 1e12");
    if (rotation.size() != 3) return QObject::tr("rotation is not three rows");
    for (int r = 0; r < 3; ++r) {
        const QJsonArray row = rotation[r].toArray();
        if (row.size() != 3) return QObject::tr("rotation is not three rows of three");
        for (int k = 0; k < 3; ++k) {
            if (!sane(row[k], 2.0)) return QObject::tr("rotation holds a number out of [-2, 2]");
            c.takeToMesh.R(r, k) = row[k].toDouble();
        }
    }
    // A rotation, not any matrix: a hostile one would shear the take out of shape.
    if (!(c.takeToMesh.R * c.takeToMesh.R.transpose()).isIdentity(1e-3))
        return QObject::tr("rotation is not orthonormal");
    c.takeToMesh.scale = o["scale"].toDouble();
    c.takeToMesh.t = Vec3(t[0].toDouble(), t[1].toDouble(), t[2].toDouble());
    c.frame = o["calibration_frame"].toInt(-1);
    c.residual = o["residual"].toDouble();
    c.visibleMarkers = o["visible_markers"].toInt();
    return {};
}

// Every option is written whatever the method, so that switching back to one finds its options
// as they were. Core's table (TakeOptionsJson) writes, reads and checks them.
QJsonObject settingsJson(const TakeSolveOptions& o) {
    return QJsonDocument::fromJson(QByteArray::fromStdString(toJson(o).dump())).object();
}

// Absent keys keep their defaults, so older projects still load; old keys and method names read
// as today's. False with *error naming the key for a value of the wrong type or out of range.
bool readSettings(const QJsonObject& o, TakeSolveOptions& settings, QString* error) {
    try {
        const auto json =
            nlohmann::json::parse(QJsonDocument(o).toJson(QJsonDocument::Compact).toStdString());
        fromJson(json, settings, "settings");
    } catch (const std::exception& e) {
        *error = QString::fromStdString(e.what());
        return false;
    }
    return true;
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

// What a JSON value is, in the words of the messages below.
QString kindOf(const QJsonValue& v) {
    switch (v.type()) {
        case QJsonValue::Null:
            return QObject::tr("null");
        case QJsonValue::Bool:
            return QObject::tr("true or false");
        case QJsonValue::Double:
            return QObject::tr("a number");
        case QJsonValue::String:
            return QObject::tr("a string");
        case QJsonValue::Array:
            return QObject::tr("an array");
        case QJsonValue::Object:
            return QObject::tr("an object");
        default:
            return QObject::tr("missing");
    }
}

// Empty when `v` is absent or of one of `types`; otherwise what it is and what belongs there.
QString wrongType(const QString& name, const QJsonValue& v,
                  std::initializer_list<QJsonValue::Type> types) {
    if (v.isUndefined()) return {};
    QStringList wanted;
    for (const QJsonValue::Type type : types) {
        if (v.type() == type) return {};
        wanted << (type == QJsonValue::Null ? QObject::tr("null") : kindOf(QJsonValue(type)));
    }
    return QObject::tr("%1 is %2, not %3").arg(name, kindOf(v), wanted.join(QObject::tr(" or ")));
}

// A key the app writes as one type, edited by hand into another ("mesh": "walker.obj", a map
// pasted as an array) read as absent: the project opened without that part, or with the map
// file's markers for the project's, and the next save wrote it so. Absent keys are an empty
// session's; a "mesh" or "take" without its "file" is a typo.
QString wrongKey(const QJsonObject& root) {
    using T = QJsonValue::Type;
    const auto quoted = [](const char* key) { return QStringLiteral("\"%1\"").arg(key); };
    const auto inner = [&](const char* outer, const char* key) {
        return QObject::tr("%1's %2").arg(quoted(outer), quoted(key));
    };
    QString why = wrongType(quoted("version"), root["version"], {T::Double});
    for (const char* key : {"mesh", "take", "correspondence"}) {
        if (why.isEmpty()) why = wrongType(quoted(key), root[key], {T::Object});
        if (why.isEmpty() && root[key].isObject()) {
            const QJsonObject o = root[key].toObject();
            if (key != std::string_view("correspondence") && !o.contains("file"))
                why = QObject::tr("%1 has no %2").arg(quoted(key), quoted("file"));
            if (why.isEmpty()) why = wrongType(inner(key, "file"), o["file"], {T::String});
        }
    }
    const QJsonObject mesh = root["mesh"].toObject(), map = root["correspondence"].toObject();
    if (why.isEmpty()) why = wrongType(inner("mesh", "group"), mesh["group"], {T::String});
    if (why.isEmpty())
        why = wrongType(inner("correspondence", "modified"), map["modified"], {T::Bool});
    if (why.isEmpty())
        why = wrongType(inner("correspondence", "map"), map["map"], {T::Object, T::Null});
    if (why.isEmpty())
        why = wrongType(quoted("alignment"), root["alignment"], {T::Object, T::Null});
    if (why.isEmpty()) why = wrongType(quoted("settings"), root["settings"], {T::Object});
    if (why.isEmpty()) why = wrongType(quoted("view"), root["view"], {T::Object});
    return why;
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
    const QByteArray json = toJson(document, path);
    QSaveFile file(path);
    // Flushed before commit(): Qt 6.4's commit() renames over the project even when flushing
    // its buffer failed (a full disk), which left an empty project and reported success.
    if (!file.open(QIODevice::WriteOnly) || file.write(json) != json.size() || !file.flush() ||
        !file.commit()) {
        if (error)
            *error = QObject::tr("%1: cannot save the project (%2)").arg(path, file.errorString());
        return false;
    }
    return true;
}

bool load(Document& document, const QString& path, QString* error, QString* missing,
          QString* missingFile, const QMap<QString, QString>& located, bool setMapAside,
          QString* setAside) {
    auto fail = [&](const QString& why) {
        if (error) *error = path + ": " + why;
        return false;
    };
    // A file moved or deleted since the project was saved: the reader's message would not say it
    // in the words the user needs.
    const QString project = QFileInfo(path).fileName();
    auto gone = [&](const QString& file, const QString& sentence) {
        if (QFileInfo::exists(file)) return false;
        if (missing) *missing = sentence.arg(file, project);
        if (missingFile) *missingFile = file;
        return true;
    };
    // As the core's loaders refuse them: opening a FIFO would wait for a writer for ever.
    if (const std::string why = notARegularFile(path.toStdString(), kKind); !why.empty())
        return fail(QString::fromStdString(why));
    QFile file(path);
    if (!file.open(QIODevice::ReadOnly)) return fail(file.errorString());
    QJsonParseError parseError;
    const QByteArray bytes = file.readAll();
    const QJsonDocument json = QJsonDocument::fromJson(bytes, &parseError);
    if (json.isNull()) {
        // A line and column, as the map reader gives them: a project fixed by hand is fixed in
        // a text editor, which counts lines, not bytes.
        const QByteArray before = bytes.left(parseError.offset);
        return fail(QObject::tr("not JSON (%1 at line %2, column %3)")
                        .arg(parseError.errorString())
                        .arg(before.count('\n') + 1)
                        .arg(before.size() - before.lastIndexOf('\n')));
    }
    if (!json.isObject()) return fail(QObject::tr("not a Boneless project (not a JSON object)"));
    const QJsonObject root = json.object();
    if (root["format"].toString() != kFormat)
        return fail(QObject::tr("not a Boneless project (format is not \"%1\")").arg(kFormat));
    if (const QString why = wrongKey(root); !why.isEmpty()) return fail(why);
    if (root["version"].toInt() != kVersion)
        return fail(QObject::tr("project version %1 is not supported (this Boneless reads %2)")
                        .arg(root["version"].toInt())
                        .arg(kVersion));

    const QDir dir = QFileInfo(path).absoluteDir();
    Document::State state;
    QString why;
    const QJsonObject mesh = root["mesh"].toObject();
    // A file the user located elsewhere is read, and saved next, in place of the one named.
    const auto at = [&located](const QString& file) { return located.value(file, file); };
    if (const QString m = at(resolve(dir, mesh["file"].toString())); !m.isEmpty()) {
        if (gone(m, QObject::tr("The mesh %1 named by %2 is missing.")))
            return fail(QObject::tr("no such mesh file: %1").arg(m));
        if (!Document::readMeshFile(m, mesh["group"].toString(), state, &why)) return fail(why);
    }
    if (const QString t = at(resolve(dir, root["take"].toObject()["file"].toString()));
        !t.isEmpty()) {
        if (gone(t, QObject::tr("The take %1 named by %2 is missing.")))
            return fail(QObject::tr("no such take file: %1").arg(t));
        if (!Document::readTakeFile(t, state, &why)) return fail(why);
    }
    const QJsonObject correspondence = root["correspondence"].toObject();
    state.mapPath = at(resolve(dir, correspondence["file"].toString()));
    if (correspondence["map"].isObject()) {
        if (!readEmbeddedMap(correspondence["map"].toObject(), state.map, &why)) return fail(why);
    } else if (!state.mapPath.isEmpty()) {
        if (gone(state.mapPath, QObject::tr("The correspondence %1 named by %2 is missing.")))
            return fail(QObject::tr("no such correspondence file: %1").arg(state.mapPath));
        try {
            state.map = Correspondence::read(state.mapPath.toStdString());
        } catch (const std::exception& e) {
            return fail(QString::fromStdString(e.what()));
        }
    }
    // A mesh re-exported since with other vertices (the map records how many it was made for),
    // or a map with an entry past the mesh's last vertex: the headline said only that the project
    // could not be opened. It names the map and the mesh, the one the map was made for can be
    // located in its place, or the project opened without the map to map the mesh anew.
    bool mapSetAside = false;
    if (state.hasMesh && !state.map.markers.empty()) {
        const int count = state.mesh.vertexCount();
        const bool otherMesh = state.map.meshVertices != 0 && state.map.meshVertices != count;
        const auto past = std::find_if(state.map.markers.begin(), state.map.markers.end(),
                                       [count](const auto& m) { return m.vertex >= count; });
        // Core's own check, in its words: also a face point on a face the mesh does not have, or
        // whose corners are other vertices now (the same vertices, faces triangulated otherwise).
        QString misfit;
        try {
            state.map.checkMesh(count, state.meshPath.toStdString(), &state.mesh);
        } catch (const std::exception& e) {
            misfit = QString::fromStdString(e.what());
        }
        if (!misfit.isEmpty()) {
            const bool inProject = correspondence["map"].isObject();
            const QString map = inProject ? QObject::tr("The map in %1").arg(project)
                                          : QObject::tr("The map %1 named by %2")
                                                .arg(QFileInfo(state.mapPath).fileName(), project);
            const QString why =
                !otherMesh && past == state.map.markers.end()
                    ? QObject::tr("%1 does not fit %2: %3").arg(map, state.meshPath, misfit)
                : otherMesh ? QObject::tr(
                                  "%1 was made for another mesh than %2, which has %3 "
                                  "vertices now.")
                                  .arg(map, state.meshPath)
                                  .arg(count)
                            : QObject::tr(
                                  "%1 points past %2: marker %3 is on vertex %4, and it has "
                                  "%5 vertices.")
                                  .arg(map, state.meshPath, QString::fromStdString(past->label))
                                  .arg(past->vertex)
                                  .arg(count);
            if (!setMapAside) {
                if (missing) *missing = why;
                if (missingFile) *missingFile = resolve(dir, mesh["file"].toString());
                return fail(misfit);
            }
            // Kept where it is: its own file left as it was, or a copy of the project's, which
            // the next save would write over.
            QString keptIn = state.mapPath;
            if (inProject || !QFileInfo::exists(keptIn)) {
                const QString stem = QFileInfo(path).completeBaseName();
                keptIn = dir.absoluteFilePath(stem + ".set-aside.map.json");
                for (int n = 2; QFileInfo::exists(keptIn); ++n)
                    keptIn =
                        dir.absoluteFilePath(QString("%1.set-aside-%2.map.json").arg(stem).arg(n));
                try {
                    state.map.write(keptIn.toStdString());
                } catch (const std::exception& e) {
                    return fail(QString::fromStdString(e.what()));
                }
            }
            if (setAside)
                *setAside = QObject::tr(
                                "%1 Opened without it, to be mapped anew; the map is kept "
                                "in %2.")
                                .arg(why, keptIn);
            state.map = Correspondence();
            state.mapPath.clear();
            mapSetAside = true;
        }
    }
    // The alignment was fitted with the map set aside.
    if (root["alignment"].isObject() && !mapSetAside) {
        Calibration c;
        const QString wrong = readAlignment(root["alignment"].toObject(), c);
        if (!wrong.isEmpty()) return fail(QObject::tr("the alignment's %1").arg(wrong));
        state.alignment = c;
    }
    if (!readSettings(root["settings"].toObject(), state.settings, &why)) return fail(why);
    state.viewSettings = root["view"].toObject().toVariantMap();
    if (!document.restoreState(std::move(state))) return fail(document.lastError());
    return true;
}

}  // namespace boneless::ui::Project
