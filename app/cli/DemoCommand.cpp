// boneless-cli demo: writes the project's generated demo (a creature and its true motion).
#include <cstdio>
#include <filesystem>
#include <memory>

#include "Commands.h"
#include "boneless/DemoCreature.h"
#include "boneless/Error.h"
#include "boneless/ObjWriter.h"

using namespace boneless;

void registerDemoCommand(CLI::App& app) {
    struct Args {
        std::string out;
        int frames = 60;
    };
    auto args = std::make_shared<Args>();
    CLI::App* cmd = app.add_subcommand(
        "demo", "Write the generated demo creature's true motion as one OBJ per frame");
    cmd->add_option("--out", args->out, "Output folder (created if missing)")->required();
    cmd->add_option("--frames", args->frames, "Number of frames")->check(CLI::Range(1, 100000));
    cmd->callback([args] {
        std::error_code ec;
        std::filesystem::create_directories(args->out, ec);
        if (ec) throw Error(args->out + ": cannot create the folder (" + ec.message() + ")");
        const DemoCreature demo = makeDemoCreature(args->frames);
        for (int t = 0; t < static_cast<int>(demo.frames.size()); ++t) {
            char name[32];
            std::snprintf(name, sizeof name, "creature_%04d.obj", t);
            writeObj(args->out + "/" + name, demo.frames[t], demo.rest.F,
                     "Boneless generated demo creature, frame " + std::to_string(t));
        }
        std::printf("%s: %zu frames of %d vertices, %d faces\n", args->out.c_str(),
                    demo.frames.size(), demo.rest.vertexCount(), demo.rest.faceCount());
    });
}
