#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <new>
#include <string>
#include <system_error>

#include "BonelessVersion.h"
#include "Commands.h"
#include "OptionFlags.h"
#include "TakeJob.h"
#include "boneless/Error.h"

namespace {

// Every run, failed or not, --help too, exits at once once its output is flushed: its files were
// closed as it returned or the error unwound. A normal exit runs OpenBLAS's library destructor,
// which joins its worker threads; under a tight ulimit -v (150 MB here) a worker that could not
// map its 128 MB buffer retries for ever (blas_memory_alloc in OpenBLAS's driver/others/memory.c
// loops until an allocator succeeds), so a demo or solve that had written everything spun at full
// CPU without end instead of exiting.
[[noreturn]] void leave(int code) {
    errno = 0;
    std::cout.flush();
    const bool lost = std::fflush(stdout) != 0 || std::ferror(stdout) || std::cout.fail();
    const int why = errno;  // the reason when the last bytes failed; a write before may have
    std::cerr.flush();
    std::fflush(nullptr);
    // A result that did not reach its file (`inspect --json > take.json` on a full disk) is no
    // success: the file is cut short.
    if (lost && code == 0) {
        std::fprintf(stderr, "boneless-cli: writing to standard output failed%s%s%s\n",
                     why != 0 ? " (" : "", why != 0 ? std::strerror(why) : "", why != 0 ? ")" : "");
        std::_Exit(1);
    }
    std::_Exit(code);
}

[[noreturn]] void fail(int code, const std::string& message) {
    std::cerr << "boneless-cli: " << message << std::endl;
    leave(code);
}

}  // namespace

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
    // An old flag's refusal names its new one, above the pointer to --help.
    app.failure_message([](const CLI::App* parsed, const CLI::Error& e) {
        std::string message = CLI::FailureMessage::simple(parsed, e);
        std::string hints;
        for (const std::string& hint : renamedFlagHints(*parsed)) hints += hint + "\n";
        return message.insert(message.find('\n') + 1, hints);
    });
    registerEvalCommand(app);
    registerDemoCommand(app);
    registerMapCommand(app);
    registerSolveCommand(app);
    registerInspectCommand(app);
    registerBatchCommand(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // --help is 0; a bad flag is bad input, 1 as every other, not CLI11's own 105 or 109.
        leave(app.exit(e) == 0 ? 0 : 1);
    } catch (const TakeJobInterrupted& e) {
        fail(128 + e.signal, e.what());  // what a shell reports for a job a signal ended
    } catch (const boneless::Error& e) {
        fail(1, e.what());
    } catch (const std::bad_alloc&) {
        fail(3, "out of memory (the machine's, a cgroup's, or ulimit -v)");
    } catch (const std::system_error& e) {
        fail(3, std::string("the system refused: ") + e.what() +
                    " (starting a thread or opening a file; is ulimit -v or -u low?)");
    } catch (const std::exception& e) {
        fail(2, std::string("internal error: ") + e.what());
    }
    leave(0);
}
