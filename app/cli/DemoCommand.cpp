// boneless-cli demo: writes the project's generated demo (a walking body, its take, its map, its
// truth).
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "Commands.h"
#include "OptionFlags.h"
#include "boneless/DemoFiles.h"
#include "boneless/Error.h"
#include "boneless/Text.h"

using namespace boneless;

void registerDemoCommand(CLI::App& app) {
    struct Args {
        std::string out;
        int frames = 60;
        int detail = 1;
        double offsetMm = 10.0;
        bool force = false;
    };
    auto args = std::make_shared<Args>();
    CLI::App* cmd = app.add_subcommand(
        "demo",
        "Write the generated demo, a human body walking: walker.obj (rest pose), walker.c3d (a "
        "39-marker Plug-in Gait style set, with gaps), walker.map.json (the correspondence) and "
        "truth/ (the true motion, one OBJ per frame)");
    cmd->add_option("--out", args->out, "Output folder (created if missing)")
        ->required()
        ->check(aPath());
    // A count, named apart from the range A:B that solve, eval and batch call --frames (which
    // demo's old name for it now hints at).
    cmd->add_option("--frame-count", args->frames,
                    withDefault("How many frames the take has (1 to 100000)", args->frames))
        ->check(numberFrom(1, 100000, true));
    // Markers sit on the skin or a few centimetres off it (a bulky suit); beyond 10 cm a marker
    // is no longer the body's.
    cmd->add_option("--offset-mm", args->offsetMm,
                    withDefault("How far the markers sit off the skin (0 to 100)", args->offsetMm))
        ->check(numberFrom(0, 100));
    cmd->add_option("--detail", args->detail,
                    withDefault("Resolution, 1 to 4: each step up has 4 times the faces (1 = 6,848 "
                                "faces)",
                                args->detail))
        ->check(numberFrom(1, 4, true));
    cmd->add_flag("--force", args->force,
                  "Replace the demo's files in --out that differ from the ones this run writes "
                  "(an edited map, a take of another length), and remove its truth frames past "
                  "--frame-count");
    cmd->callback([args] {
        // A map the user edited there is not the demo's to replace unasked;
        // files as this run would write them are replaced by the same bytes.
        const std::vector<std::string> differ =
            args->force ? std::vector<std::string>()
                        : demoFilesThatDiffer(args->out, args->frames, args->offsetMm, true,
                                              args->detail, DemoSubject::Walker);
        if (!differ.empty()) {
            constexpr std::size_t kListed = 5;
            std::string named =
                joined({differ.begin(), differ.begin() + std::min(kListed, differ.size())});
            if (differ.size() > kListed)
                named += " and " + plural(long(differ.size() - kListed), "more file", "more files");
            throw Error(args->out + ": " + named + (differ.size() == 1 ? " differs" : " differ") +
                        " from what this demo writes (edited, or written with other --frame-count, "
                        "--offset-mm or --detail); nothing was written: give --force to replace " +
                        (differ.size() == 1 ? "it" : "them") + ", or another --out");
        }
        const DemoFiles demo = writeDemoFiles(args->out, args->frames, args->offsetMm, true,
                                              args->detail, DemoSubject::Walker);
        const std::string frames = plural(demo.frames, "frame");
        std::printf(
            "%s: walker.obj (%d vertices, %d faces), walker.c3d (%d markers, %s at %g Hz), "
            "walker.map.json, truth/ (%s)\n",
            args->out.c_str(), demo.vertices, demo.faces, demo.markers, frames.c_str(), demo.rate,
            frames.c_str());
    });
}
