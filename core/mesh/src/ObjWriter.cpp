#include "boneless/ObjWriter.h"

#include <unistd.h>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "boneless/Error.h"

namespace boneless {

void writeFileAtomically(const std::string& path, const std::string& contents) {
    const std::string temporary = path + ".tmp" + std::to_string(::getpid());
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out) throw Error(path + ": cannot be written (cannot create " + temporary + ")");
        out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
        out.flush();
        if (!out) {
            std::remove(temporary.c_str());
            throw Error(path + ": writing failed (disk full?)");
        }
    }
    std::error_code ec;
    std::filesystem::rename(temporary, path, ec);
    if (ec) {
        std::remove(temporary.c_str());
        throw Error(path + ": cannot be written (" + ec.message() + ")");
    }
}

void writeObj(const std::string& path, const Positions& positions, const Faces& faces,
              const std::string& comment) {
    std::string text;
    text.reserve(static_cast<size_t>(positions.rows()) * 60 +
                 static_cast<size_t>(faces.rows()) * 24);
    if (!comment.empty()) text += "# " + comment + "\n";
    char buffer[32];
    for (int v = 0; v < positions.rows(); ++v) {
        text += 'v';
        for (int c = 0; c < 3; ++c) {
            text += ' ';
            // Shortest representation that reads back to the same double.
            auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, positions(v, c));
            text.append(buffer, end);
        }
        text += '\n';
    }
    for (int f = 0; f < faces.rows(); ++f) {
        text += 'f';
        for (int c = 0; c < 3; ++c) {
            text += ' ';
            text += std::to_string(faces(f, c) + 1);
        }
        text += '\n';
    }
    writeFileAtomically(path, text);
}

}  // namespace boneless
