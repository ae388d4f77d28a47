// boneless-cli map suggest: complete a partial marker-to-vertex map from an aligned take.
#include <cstdio>
#include <memory>

#include "Commands.h"
#include "boneless/C3dReader.h"
#include "boneless/Error.h"
#include "boneless/MarkerSuggestion.h"
#include "boneless/MeshReader.h"

using namespace boneless;

void registerMapCommand(CLI::App& app) {
    struct Args {
        std::string mesh, group, c3d, map, out;
    };
    auto args = std::make_shared<Args>();
    CLI::App* map = app.add_subcommand("map", "Author marker-to-vertex correspondence files");
    map->require_subcommand(1);
    CLI::App* suggest = map->add_subcommand(
        "suggest", "Propose the nearest vertex for every marker the partial map does not map");
    suggest->add_option("--mesh", args->mesh, "Rest mesh (OBJ, PLY, OFF, STL)")->required();
    suggest->add_option("--group", args->group, "OBJ group to use as the mesh");
    suggest->add_option("--c3d", args->c3d, "The take")->required();
    suggest->add_option("--map", args->map, "Partial map with at least 4 markers")->required();
    suggest->add_option("--out", args->out, "Where to write the completed map")->required();
    suggest->callback([args] {
        MeshReadOptions options;
        options.group = args->group;
        const TriMesh mesh = readMesh(args->mesh, options).mesh;
        const C3dTake take = readC3d(args->c3d);
        const Correspondence partial = Correspondence::read(args->map);
        const Suggestion s = suggestMappings(mesh, take, partial);
        s.map.write(args->out);
        std::printf(
            "%s: %zu markers (%d suggested), aligned at frame %d (%d markers visible), "
            "RMS residual %.4g mesh units, scale %.6g\n",
            args->out.c_str(), s.map.markers.size(), s.suggested, s.calibration.frame,
            s.calibration.visibleMarkers, s.calibration.residual, s.calibration.takeToMesh.scale);
    });
}
