#include "boneless/ObjWriter.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "MtlReader.h"
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

void checkWritable(const std::string& path) {
    const std::string temporary = temporaryFor(path);
    if (!std::ofstream(temporary, std::ios::binary | std::ios::trunc))
        throw Error(path + ": cannot be written (" + std::strerror(errno) + ")");
    std::remove(temporary.c_str());
}

namespace {

// Shortest representation that reads back to the same double.
void appendNumber(std::string& text, double value) {
    char buffer[32];
    auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
    text.append(buffer, end);
}

bool isWhitespace(char c) {
    return std::isspace(static_cast<unsigned char>(c)) != 0;
}

bool hasWhitespace(const std::string& name) {
    return std::any_of(name.begin(), name.end(), isWhitespace);
}

std::string contentsOf(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// How a file written into `folder` names `file` (absolute): relative to the folder where it can.
std::string nameFrom(const std::filesystem::path& folder, const std::string& file) {
    const std::filesystem::path relative = std::filesystem::path(file).lexically_relative(folder);
    return relative.empty() ? file : relative.string();
}

// `contents` as a file of `folder` named like `name` without whitespace: the first of name,
// name_2, ... that is free or already holds them. Its file name.
std::string placeCopy(const std::filesystem::path& folder, std::string name,
                      const std::string& contents) {
    std::replace_if(name.begin(), name.end(), isWhitespace, '_');
    const std::filesystem::path base(name);
    for (int k = 1;; ++k) {
        const std::string candidate =
            k == 1 ? name
                   : base.stem().string() + "_" + std::to_string(k) + base.extension().string();
        const std::filesystem::path file = folder / candidate;
        std::error_code error;
        if (!std::filesystem::exists(file, error)) {
            writeFileAtomically(file.string(), contents);
            return candidate;
        }
        if (std::filesystem::is_regular_file(file, error) && contentsOf(file) == contents)
            return candidate;
    }
}

void appendPolygons(std::string& text, const SourceFaces& source, const std::string& path) {
    // Resolved first, as the library paths are: lexically_relative does not resolve "out/../x"
    // or a link in the base.
    const std::filesystem::path folder = detail::resolvedPath(path).parent_path();
    for (const std::string& lib : source.materialLibraries)
        text += "mtllib " + nameFrom(folder, lib) + "\n";
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

SourceFaces withLibraryCopies(const SourceFaces& source, const std::string& folder) {
    SourceFaces out = source;
    const std::filesystem::path dir = detail::resolvedPath(folder);
    // A texture keeps its path from the copy unless that path holds whitespace too.
    const auto textureName = [&](const std::string& texture) {
        const std::string named = nameFrom(dir, texture);
        std::error_code error;
        if (!hasWhitespace(named) || !std::filesystem::is_regular_file(texture, error))
            return named;
        return placeCopy(dir, std::filesystem::path(texture).filename().string(),
                         contentsOf(texture));
    };
    for (std::string& library : out.materialLibraries) {
        std::error_code error;
        if (!hasWhitespace(nameFrom(dir, library)) ||
            !std::filesystem::is_regular_file(library, error))
            continue;
        const std::string copy = "# Boneless: a copy of " + library +
                                 " named without spaces, which an OBJ's mtllib cannot hold\n" +
                                 detail::relocatedLibrary(library, textureName);
        library = (dir / placeCopy(dir, std::filesystem::path(library).filename().string(), copy))
                      .string();
    }
    return out;
}

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
