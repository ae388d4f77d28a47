// boneless-cli demo: writes the project's generated demo (a creature, its take, its map, its
// truth).
#include <cstdio>
#include <filesystem>
#include <memory>

#include "Commands.h"
#include "boneless/C3dWriter.h"
#include "boneless/DemoCreature.h"
#include "boneless/DemoTake.h"
#include "boneless/Error.h"
#include "boneless/ObjWriter.h"

using namespace boneless;

void registerDemoCommand(CLI::App& app) {
    struct Args {
        std::string out;
        int frames = 60;
        double offsetMm = 10.0;
    };
    auto args = std::make_shared<Args>();
    CLI::App* cmd = app.add_subcommand(
        "demo",
        "Write the generated demo: creature.obj (rest pose), creature.c3d (its markers, with "
        "gaps), creature.map.json (the correspondence) and truth/ (the true motion, one OBJ per "
        "frame)");
    cmd->add_option("--out", args->out, "Output folder (created if missing)")->required();
    cmd->add_option("--frames", args->frames, "Number of frames")->check(CLI::Range(1, 100000));
    cmd->add_option("--offset-mm", args->offsetMm, "How far the markers sit off the skin");
    cmd->callback([args] {
        namespace fs = std::filesystem;
        const fs::path out(args->out), truth = out / "truth";
        std::error_code ec;
        fs::create_directories(truth, ec);
        if (ec) throw Error(args->out + ": cannot create the folder (" + ec.message() + ")");
        const DemoCreature demo = makeDemoCreature(args->frames);
        const DemoTake take = makeDemoTake(demo, 30, args->offsetMm);
        writeObj((out / "creature.obj").string(), demo.rest.V, demo.rest.F,
                 "Boneless generated demo creature, rest pose (decimetres, z up)");
        writeC3d(take.take, (out / "creature.c3d").string());
        take.map.write((out / "creature.map.json").string());
        for (int t = 0; t < static_cast<int>(demo.frames.size()); ++t) {
            char name[32];
            std::snprintf(name, sizeof name, "creature_%04d.obj", t);
            writeObj((truth / name).string(), demo.frames[t], demo.rest.F,
                     "Boneless generated demo creature, true pose of frame " + std::to_string(t));
        }
        std::printf(
            "%s: creature.obj (%d vertices, %d faces), creature.c3d (%zu markers, %zu "
            "frames at %g Hz), creature.map.json, truth/ (%zu frames)\n",
            args->out.c_str(), demo.rest.vertexCount(), demo.rest.faceCount(),
            take.take.points.size(), take.take.frameCount(), take.take.rate, demo.frames.size());
    });
}
