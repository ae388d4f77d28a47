// boneless-cli map suggest: complete a partial marker-to-vertex map from the take.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <optional>
#include <utility>

#include "Commands.h"
#include "OptionFlags.h"
#include "TakeJob.h"
#include "boneless/ActorCalibration.h"
#include "boneless/C3dReader.h"
#include "boneless/Error.h"
#include "boneless/InputFile.h"
#include "boneless/MarkerSuggestion.h"
#include "boneless/MeshReader.h"
#include "boneless/ObjWriter.h"
#include "boneless/OutputFolder.h"
#include "boneless/SuggestionCheck.h"
#include "boneless/TakeExport.h"
#include "boneless/TakeOptionsJson.h"
#include "boneless/Text.h"

using namespace boneless;

void registerMapCommand(CLI::App& app) {
    struct Args {
        std::string mesh, group, c3d, map, out, check;
        double toleranceMm = 30;
        bool force = false;
        // --mesh-up and --take-units, as solve reads them.
        nlohmann::json options = nlohmann::json::object();
    };
    auto args = std::make_shared<Args>();
    CLI::App* map = app.add_subcommand("map", "Author marker-to-vertex correspondence files");
    map->require_subcommand(1);
    CLI::App* suggest = map->add_subcommand(
        "suggest",
        "Fit the mesh to the take from the mapped markers and propose a vertex for every other "
        "marker, flagging the ones to review");
    suggest->add_option("--mesh", args->mesh, "Rest mesh (OBJ, PLY, OFF, STL)")
        ->required()
        ->check(aPath());
    suggest->add_option("--group", args->group, "OBJ group to use as the mesh");
    suggest->add_option("--c3d", args->c3d, "The take")->required()->check(aPath());
    suggest->add_option("--map", args->map, "Partial map with at least 4 markers")
        ->required()
        ->check(aPath());
    suggest->add_option("--out", args->out, "Where to write the completed map")
        ->required()
        ->check(aPath());
    CLI::Option* check =
        suggest
            ->add_option("--check", args->check,
                         "A map known to be right: print how near the proposals land to it")
            ->check(aPath());
    suggest
        ->add_option("--tolerance-mm", args->toleranceMm,
                     withDefault("With --check: how near counts as landing (0.1 to 1000)",
                                 args->toleranceMm))
        ->check(numberFrom(0.1, 1000))
        ->needs(check);
    addOptionFlag(suggest, args->options, toJson(TakeSolveOptions{}), "mesh_up");
    addOptionFlag(suggest, args->options, toJson(TakeSolveOptions{}), "take_units");
    suggest->add_flag("--force", args->force,
                      "Replace an --out that differs from the map this run writes (a map reviewed "
                      "by hand)");
    suggest->callback([args] {
        // `--out take.c3d` replaced the take, `--out ref.json --check ref.json` the map to check
        // against: refused before anything is read.
        for (const auto& [what, input] :
             {std::pair<const char*, const std::string*>{"mesh", &args->mesh},
              {"take", &args->c3d},
              {"map", &args->map},
              {"reference map", &args->check}})
            if (!input->empty() && sameFile(args->out, *input))
                throw Error(args->out + ": the completed map would replace the " + what + " " +
                            *input + "; give --out another file");
        // A map reviewed by hand, given as --out by mistake, is not replaced unasked (as demo
        // keeps an edited map); the same map again is. Refused before the fit when it cannot be
        // what this run writes (no map at all), else once the map is made, before it is written.
        const bool keep = !args->force && std::filesystem::exists(args->out);
        const auto refuse = [&] {
            return Error(args->out +
                         ": differs from the map this run suggests (reviewed by hand, or suggested "
                         "from other inputs); nothing was written: give --force to replace it, or "
                         "another --out");
        };
        if (const std::string why = notARegularFile(args->out, "map");
            std::filesystem::exists(args->out) && !why.empty())
            throw Error(args->out + ": " + why);
        if (keep) {
            try {
                Correspondence::read(args->out);
            } catch (const Error&) {
                throw refuse();
            }
        }
        checkWritable(args->out);  // not after the fit's minute
        // The take first: one in other units than it says is refused before the mesh is read.
        C3dTake take = readC3d(args->c3d);
        applyTakeUnits(take, args->options);
        refuseDoubtfulUnits(take, "nothing was written");
        MeshReadOptions options;
        options.group = args->group;
        const TriMesh mesh = readMesh(args->mesh, options).mesh;
        const Correspondence partial = Correspondence::read(args->map);
        // Read before the map is written, so that a run that fails leaves nothing behind.
        const std::optional<Correspondence> truth =
            args->check.empty() ? std::nullopt
                                : std::optional<Correspondence>(Correspondence::read(args->check));
        checkMapFitsMesh(partial, mesh, args->mesh, args->group);
        for (const Correspondence* map : {&partial, truth ? &*truth : nullptr})
            for (const std::string& w : map ? map->warnings : std::vector<std::string>())
                std::fprintf(stderr, "warning: %s\n", w.c_str());
        // A reference made for another mesh compares vertex numbers that name other places.
        if (truth) checkMapFitsMesh(*truth, mesh, args->mesh, args->group);
        TakeSolveOptions solveOptions;
        fromJson(args->options, solveOptions, "options");
        Suggestion s = suggestMappings(mesh, take, partial, solveOptions.meshUp);
        // The map records the mesh it was made on, as the app's maps do when saved: the partial
        // map's own record named another file, or a group of a file that has none by that name.
        s.map.meshFile = std::filesystem::path(args->mesh).filename().string();
        s.map.meshGroup = args->group;
        s.map.meshVertices = mesh.vertexCount();
        if (keep) {
            std::ifstream in(args->out, std::ios::binary);
            if (std::string{std::istreambuf_iterator<char>(in), {}} != s.map.toJson())
                throw refuse();
        }
        s.map.write(args->out);
        // Nothing fitted, no alignment worth a figure: "aligned at frame -1" said nothing.
        if (s.proposals.empty() && s.offBody.empty() && s.fittedFrame < 0) {
            const char* why =
                s.calibration.frame >= 0
                    ? "no frame the mesh was fitted at shows an unmapped marker"
                : s.otherSubjects.empty()
                    ? "every marker seen in the take is mapped"
                    : "every marker of the mapped markers' subject is mapped, and the take's "
                      "others are worn by another subject";
            std::printf("%s: %zu markers, nothing to suggest: %s\n", args->out.c_str(),
                        s.map.markers.size(), why);
        } else {
            std::printf(
                "%s: %zu markers (%d suggested, %d to review), aligned at frame %d (%d markers "
                "visible), RMS residual %.1f mm, scale %.6g, fitted best at frame %d\n",
                args->out.c_str(), s.map.markers.size(), s.suggested, s.needsReview,
                s.calibration.frame, s.calibration.visibleMarkers,
                s.calibration.residualMm(take.unitToMm), s.calibration.takeToMesh.scale,
                s.fittedFrame);
        }
        if (!s.offBody.empty())
            std::printf("  left unmapped, more than %g mm from the fitted body: %s\n",
                        kUnreachableMm, joined(s.offBody).c_str());
        if (!s.otherSubjects.empty())
            std::printf("  left unmapped, worn by a subject no mapped marker names: %s\n",
                        joined(s.otherSubjects).c_str());
        if (!s.sharedLabels.empty())
            std::printf("  left unmapped, each label worn by two points of the take: %s\n",
                        joined(s.sharedLabels).c_str());
        for (const Proposal& p : s.proposals)
            if (p.needsReview)
                std::printf("  review %s (vertex %d): %s\n", p.label.c_str(), p.vertex,
                            p.reviewReason.c_str());
        if (!truth) return;
        const SuggestionCheck c = checkSuggestion(mesh, take, s, *truth, args->toleranceMm);
        for (const auto& [label, mm] : c.distancesMm)
            std::printf("  %-8s %7.1f mm%s\n", label.c_str(), mm,
                        mm > args->toleranceMm ? "  off" : "");
        // "0 of 0 within 30 mm, median 0.0 mm" read as a check that passed.
        if (c.compared == 0 && !s.proposals.empty())
            throw Error(args->check + ": names none of the " +
                        plural(long(s.proposals.size()), "suggested marker") +
                        " (as the take labels them): nothing to check them against; the map "
                        "was written");
        std::printf("%d of %d within %g mm, median %.1f mm\n", c.within, c.compared,
                    args->toleranceMm, c.medianMm);
    });
}
