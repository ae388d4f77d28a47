// boneless-cli solve: a take and a mesh in, an OBJ sequence, a point cache or a glb out.
#include <memory>

#include "Commands.h"
#include "OptionFlags.h"
#include "TakeJob.h"
#include "boneless/TakeSolver.h"

void registerSolveCommand(CLI::App& app) {
    struct SolveArgs {
        TakeJob job;
        bool quiet = false;
    };
    auto args = std::make_shared<SolveArgs>();
    CLI::App* cmd = app.add_subcommand("solve", "Animate a mesh from a C3D take");
    cmd->add_option("--mesh", args->job.mesh, "Rest mesh (OBJ, PLY, OFF, STL)")
        ->required()
        ->check(aPath());
    cmd->add_option("--group", args->job.group, "OBJ group to use as the mesh");
    cmd->add_option("--c3d", args->job.c3d, "The take")->required()->check(aPath());
    cmd->add_option("--map", args->job.map, "Correspondence file (JSON)")
        ->required()
        ->check(aPath());
    cmd->add_option("--out", args->job.out, "Output folder")->required()->check(aPath());
    addTakeJobOptions(cmd, args->job);
    cmd->add_flag("--quiet", args->quiet, "No progress on stderr");
    cmd->add_flag("--force", args->job.force,
                  "Replace files in --out of the outputs' names that no Boneless export wrote "
                  "(another tool's OBJ frames, the demo's truth/), or another take's solve; an "
                  "earlier export of this take is replaced without it");
    cmd->callback([args] {
        refuseUnusedExactOptions(args->job.options, boneless::TakeSolveOptions{}.solver);
        runTakeJob(args->job, args->quiet);
    });
}
