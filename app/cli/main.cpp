#include <iostream>

#include "Commands.h"
#include "boneless/Error.h"

int main(int argc, char** argv) {
    CLI::App app{"boneless-cli: skeleton-free mesh animation from motion-capture markers"};
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
