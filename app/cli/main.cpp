#include <iostream>
#include <string>

#include "Commands.h"
#include "boneless/Error.h"

int main(int argc, char** argv) {
    CLI::App app{"boneless-cli: skeleton-free mesh animation from motion-capture markers"};
    app.set_version_flag("--version", std::string("boneless-cli ") + BONELESS_VERSION);
    app.footer(
        "A take from the capture to mesh animation:\n"
        "  boneless-cli inspect take.c3d\n"
        "  boneless-cli map suggest --mesh body.obj --c3d take.c3d --map partial.json --out "
        "map.json\n"
        "  boneless-cli solve --mesh body.obj --c3d take.c3d --map map.json --out solved/\n"
        "'boneless-cli demo --out DIR' writes a generated example to try these on; "
        "'boneless-cli SUBCOMMAND --help' describes each one.");
    app.require_subcommand(1);
    registerEvalCommand(app);
    registerDemoCommand(app);
    registerMapCommand(app);
    registerSolveCommand(app);
    registerInspectCommand(app);
    registerBatchCommand(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const boneless::Error& e) {
        std::cerr << "boneless-cli: " << e.what() << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "boneless-cli: internal error: " << e.what() << "\n";
        return 2;
    }
    return 0;
}
