#include "boneless/Correspondence.h"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <type_traits>

#include "boneless/C3dTake.h"
#include "boneless/Error.h"
#include "boneless/InputFile.h"
#include "boneless/ObjWriter.h"
#include "boneless/Text.h"
#include "boneless/TriMesh.h"

namespace boneless {

namespace {

using nlohmann::json;

constexpr const char* kFormat = "boneless-correspondence";
constexpr int kVersion = 2;  // read: 1 and 2; written: 1 unless a marker names a face point

[[noreturn]] void fail(const std::string& file, const std::string& what) {
    throw Error(file + ": " + what);
}

template <typename T>
// `where` names the object holding `key`; empty for the file's own keys ("version").
T get(const json& object, const char* key, const std::string& file, const std::string& where) {
    const std::string at = where.empty() ? "" : where + ": ";
    if (!object.contains(key))
        fail(file, (where.empty() ? "" : where + " ") + "has no \"" + key + "\"");
    try {
        const json& value = object.at(key);
        if constexpr (std::is_same_v<T, int>) {
            // get<int> would wrap 3e9 and cast 1e30 (undefined): only integers that fit.
            if (!value.is_number_integer() || value < json(INT_MIN) || value > json(INT_MAX))
                fail(file, at + "\"" + key + "\" is not a whole number in the int range");
        }
        return value.get<T>();
    } catch (const json::exception&) {
        fail(file, at + "\"" + key + "\" has the wrong type");
    }
}

// What every message calls a map entry: "marker T10", by its label, the name the user gave it
// and looks for; "markers[3]" (0-based in the file's "markers" list) while it has none to give.
// It was "marker 3:", "marker 3 (T10):" and "marker T10:" by turns, and "marker 3" could be read
// as a label.
std::string entryName(const std::string& label, std::size_t index) {
    return label.empty() ? "markers[" + std::to_string(index) + "]" : "marker " + label;
}

json withoutKeys(json object, std::initializer_list<const char*> keys) {
    for (const char* k : keys) object.erase(k);
    return object;
}

}  // namespace

Correspondence Correspondence::read(const std::string& path) {
    if (const std::string why = notARegularFile(path, "correspondence"); !why.empty())
        fail(path, why);
    std::ifstream in(path);
    if (!in)
        fail(path,
             std::string("cannot open the correspondence file (") + std::strerror(errno) + ")");
    std::stringstream text;
    text << in.rdbuf();
    return fromJson(text.str(), path);
}

Correspondence Correspondence::fromJson(const std::string& text, const std::string& path) {
    json doc;
    try {
        doc = json::parse(text);
    } catch (const json::exception& e) {  // parse errors, and numbers past double's range
        fail(path, std::string("is not valid JSON (") + e.what() + ")");
    }
    if (!doc.is_object()) fail(path, "is not a JSON object");
    if (!doc.contains("format") || !doc["format"].is_string() || doc["format"] != kFormat)
        fail(path, std::string("is not a Boneless correspondence file (\"format\" must be \"") +
                       kFormat + "\")");
    const int version = get<int>(doc, "version", path, "");
    if (version < 1 || version > kVersion)
        fail(path, "has version " + std::to_string(version) +
                       "; this Boneless reads versions 1 to " + std::to_string(kVersion));
    Correspondence c;
    c.source_ = path;
    const json mesh = doc.contains("mesh") ? doc["mesh"] : json::object();
    if (!mesh.is_object()) fail(path, "\"mesh\" must be an object");
    c.meshFile = mesh.contains("file") ? get<std::string>(mesh, "file", path, "\"mesh\"") : "";
    c.meshVertices = mesh.contains("vertices") ? get<int>(mesh, "vertices", path, "\"mesh\"") : 0;
    c.meshGroup = mesh.contains("group") ? get<std::string>(mesh, "group", path, "\"mesh\"") : "";
    if (!doc.contains("markers") || !doc["markers"].is_array())
        fail(path, "has no \"markers\" list");
    std::vector<std::string> unreadFaces;       // version 1 entries with a face point's keys
    std::map<std::string, std::size_t> labels;  // each label and vertex, and the entry that has it
    std::map<int, std::size_t> vertices;
    const json& list = doc["markers"];
    for (size_t i = 0; i < list.size(); ++i) {
        const json& m = list[i];
        if (!m.is_object()) fail(path, entryName("", i) + " is not an object");
        MarkerMapping mapping;
        mapping.label = get<std::string>(m, "label", path, entryName("", i));
        if (mapping.label.empty()) fail(path, entryName("", i) + ": \"label\" is empty");
        const std::string where = entryName(mapping.label, i);
        mapping.vertex = get<int>(m, "vertex", path, where);
        mapping.offsetMm = m.contains("offset_mm") ? get<double>(m, "offset_mm", path, where) : 0.0;
        if (!(mapping.offsetMm >= Correspondence::kMinOffsetMm &&
              mapping.offsetMm <= Correspondence::kMaxOffsetMm)) {
            // The bounds from the constants, so the message follows them.
            fail(path, where + ": \"offset_mm\" " + shortNumber(mapping.offsetMm) +
                           " is out of range (a marker sits " +
                           shortNumber(Correspondence::kMinOffsetMm) + " to " +
                           shortNumber(Correspondence::kMaxOffsetMm) + " mm off the skin)");
        }
        if (version >= 2 && m.contains("barycentric") && !m.contains("face"))
            fail(path, where + ": \"barycentric\" places it on a face, and it names no \"face\"");
        if (version >= 2 && m.contains("face")) {
            mapping.face = get<int>(m, "face", path, where);
            // get<std::array> would take the first three of a longer list, and drop the rest.
            if (m.contains("barycentric") &&
                (!m["barycentric"].is_array() || m["barycentric"].size() != 3))
                fail(path, where +
                               ": \"barycentric\" must be three numbers, none negative, that "
                               "sum to 1");
            mapping.barycentric = get<std::array<double, 3>>(m, "barycentric", path, where);
            if (mapping.face < 0)
                fail(path, where + ": face " + std::to_string(mapping.face) + " is negative");
            const auto& b = mapping.barycentric;
            if (!(b[0] >= 0 && b[1] >= 0 && b[2] >= 0) || std::abs(b[0] + b[1] + b[2] - 1) > 1e-6)
                fail(path, where +
                               ": \"barycentric\" must be three numbers, none negative, that "
                               "sum to 1");
        }
        // Version 1 files keep "face" and "barycentric" as keys of their own, unread; a "face"
        // that is a face number was meant as a point of it, and the marker sits on its vertex.
        if (version < 2 && m.contains("face") && m["face"].is_number_integer())
            unreadFaces.push_back(where + " has \"face\": " + m["face"].dump());
        mapping.extraJson =
            (version >= 2 ? withoutKeys(m, {"label", "vertex", "offset_mm", "face", "barycentric"})
                          : withoutKeys(m, {"label", "vertex", "offset_mm"}))
                .dump();
        if (mapping.vertex < 0)
            fail(path, where + ": vertex " + std::to_string(mapping.vertex) + " is negative");
        // Two entries of one label: the index is what tells them apart.
        if (const auto [at, added] = labels.emplace(mapping.label, i); !added)
            fail(path, where + " is mapped twice (" + entryName("", at->second) + " and " +
                           entryName("", i) + ")");
        if (const auto [at, added] = vertices.emplace(mapping.vertex, i); !added)
            fail(path, where + ": vertex " + std::to_string(mapping.vertex) + " already carries " +
                           entryName(c.markers[at->second].label, at->second));
        c.markers.push_back(std::move(mapping));
    }
    if (!unreadFaces.empty()) {
        const bool one = unreadFaces.size() == 1;
        c.warnings.push_back(
            path + ": " + joined(unreadFaces, "; ") + ", which only \"version\": 2 " +
            "reads: this file says \"version\": 1, so " +
            (one ? "it sits on its \"vertex\"" : "they sit on their \"vertex\"") +
            " (write \"version\": 2 to place " + (one ? "it" : "them") + " on the face)");
    }
    json extra = withoutKeys(doc, {"format", "version", "markers"});
    if (extra.contains("mesh"))
        extra["mesh"] = withoutKeys(extra["mesh"], {"file", "group", "vertices"});
    c.extraJson_ = extra.dump();
    return c;
}

std::string Correspondence::toJson() const {
    json doc = json::parse(extraJson_);
    doc["format"] = kFormat;
    bool facePoints = false;
    for (const auto& m : markers) facePoints = facePoints || m.face >= 0;
    doc["version"] = facePoints ? 2 : 1;
    json mesh = doc.contains("mesh") ? doc["mesh"] : json::object();
    // The mesh's file name may not be UTF-8 (Latin-1), which JSON cannot hold as it is.
    mesh["file"] = validUtf8(meshFile);
    if (!meshGroup.empty()) mesh["group"] = validUtf8(meshGroup);
    mesh["vertices"] = meshVertices;
    doc["mesh"] = mesh;
    json list = json::array();
    for (const auto& m : markers) {
        json entry = m.extraJson.empty() ? json::object() : json::parse(m.extraJson);
        entry["label"] = m.label;
        entry["vertex"] = m.vertex;
        entry["offset_mm"] = m.offsetMm;
        if (m.face >= 0) {
            entry["face"] = m.face;
            entry["barycentric"] = m.barycentric;
        } else if (facePoints) {
            // A version 1 entry's own "face" key, unread there, would place it (or, without a
            // "barycentric", fail the file) once the map is version 2: it sits on its vertex.
            entry.erase("face");
            entry.erase("barycentric");
        }
        list.push_back(entry);
    }
    doc["markers"] = list;
    return doc.dump(2) + "\n";
}

void Correspondence::write(const std::string& path) const {
    writeFileAtomically(path, toJson());
}

void Correspondence::checkMesh(int vertexCount, const std::string& meshPath,
                               const TriMesh* mesh) const {
    const std::string file = source_.empty() ? "correspondence" : source_;
    // A whole OBJ read where the map was made on one of its groups is the likely slip: the
    // message names the group and its file, and the caller says how to open it (a flag, a menu).
    const std::string madeOn = meshFile.empty() ? "its OBJ" : meshFile;
    if (meshVertices != 0 && meshVertices != vertexCount)
        fail(file, "was made for " +
                       (meshGroup.empty() ? "a mesh" : "group '" + meshGroup + "' of " + madeOn) +
                       " with " + std::to_string(meshVertices) + " vertices, but " + meshPath +
                       " has " + std::to_string(vertexCount));
    for (const auto& m : markers)
        if (m.vertex >= vertexCount)
            fail(file, "marker " + m.label + ": vertex " + std::to_string(m.vertex) +
                           " is out of range (" + meshPath + " has " + std::to_string(vertexCount) +
                           " vertices)");
    if (!mesh) return;
    for (const auto& m : markers) {
        if (m.face < 0) continue;
        if (m.face >= mesh->faceCount())
            fail(file, "marker " + m.label + ": face " + std::to_string(m.face) +
                           " is out of range (" + meshPath + " has " +
                           std::to_string(mesh->faceCount()) + " triangles)");
        // Any copy of a welded vertex names it (TriMesh::weldedTo).
        const auto corners = mesh->F.row(m.face);
        const int v = weldedVertex(*mesh, m.vertex);
        if (corners[0] != v && corners[1] != v && corners[2] != v)
            fail(file, "marker " + m.label + ": vertex " + std::to_string(m.vertex) +
                           " is not a corner of face " + std::to_string(m.face));
    }
}

std::string Correspondence::labelProblem(const C3dTake& take, const std::string& label) {
    const std::vector<std::size_t> named = take.pointsNamed(label);
    if (named.empty()) return {};
    // Two points with one full label: no label can say which, the subject prefix included.
    if (named.size() > 1 && take.pointsNamed(take.points[named.front()].label) == named)
        return "marker " + label + ": in " + take.file + ", " + take.sharedLabelText(named) +
               ": two points with one label, not two subjects, so no map label can say which; "
               "relabel one of them in the take";
    // A bare name two subjects wear would bind to whichever the file lists first.
    if (named.size() > 1) {
        std::vector<std::string> labels;
        for (std::size_t p : named) labels.push_back(take.points[p].label);
        return "marker " + label + " is worn by more than one subject in " + take.file + " (" +
               joined(labels) + "); write the subject prefix";
    }
    // A model's output (a joint angle, a force, a segment axis) is stored as a point too, but
    // its numbers are no place on the body: pulled to, they fling the mesh about.
    const C3dPoint& point = take.points[named.front()];
    if (point.kind != C3dPointKind::Marker)
        return "marker " + label + " names " + (point.kind == C3dPointKind::Angle ? "an " : "a ") +
               toString(point.kind) + " point of " + take.file + " (a model output), not a marker";
    return {};
}

std::vector<std::string> Correspondence::subjects(const C3dTake& take) const {
    std::vector<std::size_t> points = resolve(take);
    std::sort(points.begin(), points.end());
    std::vector<std::string> out;
    for (const std::size_t p : points) {
        const std::string& subject = take.points[p].subject;
        if (!subject.empty() && std::none_of(out.begin(), out.end(), [&](const std::string& s) {
                return c3dNameEquals(s, subject);
            }))
            out.push_back(subject);
    }
    return out;
}

std::vector<std::size_t> Correspondence::resolve(const C3dTake& take) const {
    const std::string file = source_.empty() ? "correspondence" : source_;
    std::vector<std::size_t> points;
    std::vector<std::string> unknown;
    std::map<std::size_t, std::string> bound;  // each point of the take, and the label naming it
    for (const auto& m : markers) {
        const std::vector<std::size_t> named = take.pointsNamed(m.label);
        if (named.empty()) {
            unknown.push_back(m.label);
            continue;
        }
        if (const std::string problem = labelProblem(take, m.label); !problem.empty())
            fail(file, problem);
        // "LFHD" and "walker:LFHD" are one marker: two entries would pull two vertices to it.
        if (const auto [at, added] = bound.emplace(named.front(), m.label); !added)
            fail(file, "marker " + at->second + " and marker " + m.label + " both name " +
                           take.points[named.front()].label + " of " + take.file + ": map it once");
        points.push_back(named.front());
    }
    if (unknown.empty()) return points;
    // A prefix that names no subject of the take ("other:T10" where walker wears T10) finds no
    // other subject's marker: the take's subjects say which prefix to write. One that names a
    // subject who does not wear the marker ("Daphnee:gauche_ext", worn by boite) is told whose
    // it is.
    const std::vector<std::string> subjects = take.subjects();
    std::string said;
    std::vector<std::string> worn;  // the labels of other subjects' markers of the names
    for (const std::string& label : unknown) {
        std::string subject, name;
        splitC3dLabel(label, subject, name);
        if (subject.empty() || subjects.empty()) continue;
        if (std::none_of(subjects.begin(), subjects.end(),
                         [&](const std::string& s) { return c3dNameEquals(s, subject); }))
            said = subjects.size() == 1 ? "; the take's only subject is " + subjects.front()
                                        : "; the take's subjects are " + joined(subjects);
        else
            for (std::size_t p : take.pointsNamed(name)) worn.push_back(take.points[p].label);
    }
    if (!worn.empty())
        said += "; " + joined(worn) + (worn.size() == 1 ? " is" : " are") + " in the take";
    fail(file, "labels not found in " + take.file + ": " + joined(unknown) + said);
}

const MarkerMapping* Correspondence::find(const std::string& label) const {
    for (const auto& m : markers)
        if (m.label == label) return &m;
    return nullptr;
}

}  // namespace boneless
