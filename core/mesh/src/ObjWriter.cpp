#include "boneless/ObjWriter.h"

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "boneless/Error.h"
#include "boneless/SpoolFile.h"

namespace boneless {

void writeFileAtomically(const std::string& path, const std::string& contents) {
    writeFileAtomically(path, [&](std::ostream& out) {
        out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    });
}

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
    const std::string temporary = temporaryFor(path);
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out) throw Error(path + ": cannot be written (" + std::strerror(errno) + ")");
        try {
            write(out);
        } catch (...) {
            out.close();
            std::remove(temporary.c_str());
            throw;
        }
        out.flush();
        if (!out) {
            const std::string why = writeFailure();
            std::remove(temporary.c_str());
            throw Error(path + ": writing failed (" + why + ")");
        }
    }
    std::error_code ec;
    std::filesystem::rename(temporary, path, ec);
    if (ec) {
        std::remove(temporary.c_str());
        throw Error(path + ": cannot be written (" + ec.message() + ")");
    }
}

namespace {

// Shortest representation that reads back to the same double.
void appendNumber(std::string& text, double value) {
    char buffer[32];
    auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
    text.append(buffer, end);
}

void appendPolygons(std::string& text, const SourceFaces& source, const std::string& path) {
    // Normalised first: lexically_relative does not resolve "out/../x" in the base.
    const std::filesystem::path folder =
        std::filesystem::absolute(path).lexically_normal().parent_path();
    for (const std::string& lib : source.materialLibraries) {
        const std::filesystem::path relative =
            std::filesystem::path(lib).lexically_relative(folder);
        text += "mtllib " + (relative.empty() ? lib : relative.string()) + "\n";
    }
    for (size_t t = 0; t < source.uv.size(); t += 2) {
        text += "vt ";
        appendNumber(text, source.uv[t]);
        text += ' ';
        appendNumber(text, source.uv[t + 1]);
        text += '\n';
    }
    size_t material = 0;
    for (int p = 0; p < source.polygonCount(); ++p) {
        if (material < source.materials.size() && source.materials[material].first == p)
            text += "usemtl " +
                    source.materialDefinitions[source.materials[material++].second].name + "\n";
        text += 'f';
        for (int c = source.start[p]; c < source.start[p + 1]; ++c) {
            text += ' ';
            text += std::to_string(source.corners[c] + 1);
            if (!source.uvOf.empty() && source.uvOf[c] >= 0)
                text += '/' + std::to_string(source.uvOf[c] + 1);
        }
        text += '\n';
    }
}

}  // namespace

std::string objText(const std::string& path, const Positions& positions, const Faces& faces,
                    const std::string& comment, const SourceFaces* source) {
    std::string text;
    text.reserve(static_cast<size_t>(positions.rows()) * 60 +
                 static_cast<size_t>(faces.rows()) * 24);
    if (!comment.empty()) text += "# " + comment + "\n";
    for (int v = 0; v < positions.rows(); ++v) {
        text += 'v';
        for (int c = 0; c < 3; ++c) {
            text += ' ';
            appendNumber(text, positions(v, c));
        }
        text += '\n';
    }
    // A source from another mesh would write faces that point at the wrong vertices.
    if (source && source->vertexCount == positions.rows()) {
        appendPolygons(text, *source, path);
    } else {
        for (int f = 0; f < faces.rows(); ++f) {
            text += 'f';
            for (int c = 0; c < 3; ++c) {
                text += ' ';
                text += std::to_string(faces(f, c) + 1);
            }
            text += '\n';
        }
    }
    return text;
}

void writeObj(const std::string& path, const Positions& positions, const Faces& faces,
              const std::string& comment, const SourceFaces* source) {
    writeFileAtomically(path, objText(path, positions, faces, comment, source));
}

}  // namespace boneless
