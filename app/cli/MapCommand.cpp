// boneless-cli map suggest: complete a partial marker-to-vertex map from an aligned take.
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "Commands.h"
#include "boneless/C3dReader.h"
#include "boneless/Error.h"
#include "boneless/MarkerSuggestion.h"
#include "boneless/MeshReader.h"

using namespace boneless;

void registerMapCommand(CLI::App& app) {
    struct Args {
        std::string mesh, group, c3d, map, out, check;
        double toleranceMm = 30;
    };
    auto args = std::make_shared<Args>();
    CLI::App* map = app.add_subcommand("map", "Author marker-to-vertex correspondence files");
    map->require_subcommand(1);
    CLI::App* suggest = map->add_subcommand(
        "suggest",
        "Fit the mesh to the take from the mapped markers and propose a vertex for every "
        "other marker, flagging the ones to review");
    suggest->add_option("--mesh", args->mesh, "Rest mesh (OBJ, PLY, OFF, STL)")->required();
    suggest->add_option("--group", args->group, "OBJ group to use as the mesh");
    suggest->add_option("--c3d", args->c3d, "The take")->required();
    suggest->add_option("--map", args->map, "Partial map with at least 4 markers")->required();
    suggest->add_option("--out", args->out, "Where to write the completed map")->required();
    suggest->add_option("--check", args->check,
                        "A map known to be right: print how many suggestions land near it");
    suggest
        ->add_option("--tolerance-mm", args->toleranceMm,
                     "With --check: how near counts as landing (default 30)")
        ->check(CLI::PositiveNumber);
    suggest->callback([args] {
        MeshReadOptions options;
        options.group = args->group;
        const TriMesh mesh = readMesh(args->mesh, options).mesh;
        const C3dTake take = readC3d(args->c3d);
        const Correspondence partial = Correspondence::read(args->map);
        const Suggestion s = suggestMappings(mesh, take, partial);
        s.map.write(args->out);
        std::printf(
            "%s: %zu markers (%d suggested, %d to review), aligned at frame %d (%d markers "
            "visible), RMS residual %.4g mesh units, scale %.6g, best fitted at frame %d\n",
            args->out.c_str(), s.map.markers.size(), s.suggested, s.needsReview,
            s.calibration.frame, s.calibration.visibleMarkers, s.calibration.residual,
            s.calibration.takeToMesh.scale, s.fittedFrame);
        for (const auto& m : s.map.markers) {
            const auto extra = nlohmann::json::parse(m.extraJson, nullptr, false);
            if (extra.is_object() && extra.value("needs_review", false))
                std::printf("  review %s (vertex %d): %s\n", m.label.c_str(), m.vertex,
                            extra.value("review_reason", std::string()).c_str());
        }
        if (!args->check.empty()) {
            const SuggestionCheck c = checkSuggestion(
                mesh, take, s, Correspondence::read(args->check), args->toleranceMm);
            std::printf("%d of %d suggestions within %g mm of %s (%.0f %%), median %.1f mm\n",
                        c.within, c.compared, args->toleranceMm, args->check.c_str(),
                        c.compared ? 100.0 * c.within / c.compared : 0.0, c.medianMm);
        }
    });
}
