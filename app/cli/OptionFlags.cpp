#include "OptionFlags.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "boneless/Error.h"
#include "boneless/TakeOptionsJson.h"
#include "boneless/Text.h"

using namespace boneless;

namespace {

// The flags that took their option's key as their name: the command that had the old flag, the
// old flag, the key (eval's --rigidity and --tolerance went with the methods that are gone and
// came back as the table's). solve's --rigidity never was: it gets no hint. A flag of a command's
// own, outside the table, names its new flag instead of a key: demo's --frames, a count where
// solve, eval and batch read a range A:B, became --frame-count.
struct RenamedFlag {
    const char* command;
    const char* old;
    const char* key;        // the table's option, or null
    const char* flag = "";  // the new flag when `key` is null
};
const RenamedFlag kRenamedFlags[] = {
    {"solve", "--weight", "marker_weight"},        {"solve", "--lowpass", "low_pass_hz"},
    {"solve", "--fill-gaps", "fill_gaps_s"},       {"eval", "--rigidity", "fold_guard"},
    {"eval", "--tolerance", "relative_tolerance"}, {"demo", "--frames", nullptr, "--frame-count"},
};

}  // namespace

namespace {

void addOptionFlag(CLI::App* command, nlohmann::json& given, const nlohmann::json& defaults,
                   const TakeOption& o) {
    std::string help = o.doc;
    help[0] = asciiUpper(help[0]);
    if (!o.units.empty()) help += " (" + o.units + ")";
    CLI::Option* flag = command->add_option_function<std::string>(
        optionFlag(o),
        [&given, o](const std::string& text) { given[o.key] = optionValueFromText(o, text); },
        withDefault(help, defaults.at(o.key)));
    flag->check(CLI::Validator([o](std::string& text) { return checkOptionText(o, text); }, ""));
    std::string type = o.kind == TakeOption::Kind::Integer ? "INT" : "NUMBER";
    if (o.kind == TakeOption::Kind::Choice) {
        type.clear();
        for (const std::string& c : o.choices) type += (type.empty() ? "" : "|") + c;
    }
    flag->type_name(type);
}

}  // namespace

void addOptionFlags(CLI::App* command, nlohmann::json& given, const nlohmann::json& defaults,
                    bool solverOnly) {
    for (const TakeOption& o : takeOptions())
        if (!solverOnly || o.solver) addOptionFlag(command, given, defaults, o);
}

void addOptionFlag(CLI::App* command, nlohmann::json& given, const nlohmann::json& defaults,
                   const std::string& key) {
    for (const TakeOption& o : takeOptions())
        if (o.key == key) return addOptionFlag(command, given, defaults, o);
    throw Error("no option \"" + key + "\" in the take options' table");
}

CLI::Validator numberFrom(double low, double high, bool whole) {
    char range[64];
    // A whole number's bounds in digits, as it must be typed: "to 4294967295", not "4.29497e+09".
    std::snprintf(range, sizeof range,
                  whole ? "must be a whole number from %.0f to %.0f, got "
                        : "must be a number from %g to %g, got ",
                  low, high);
    return CLI::Validator(
        [low, high, whole, range = std::string(range)](std::string& text) -> std::string {
            // A count in digits alone: CLI11 reads "1e3" as no int, and "010" as octal 8.
            double x = NAN;
            const Decimal read = readDecimal(text, x);
            if (read == Decimal::Underflow) return range + text + ", " + kUnderflowNote;
            const bool ok = read == Decimal::Number && std::isfinite(x) && x >= low && x <= high &&
                            (!whole || text.find_first_not_of("+-0123456789") == std::string::npos);
            // A word is quoted as a bad choice is ("got \"010\""); a number out of range is not.
            return ok ? std::string()
                      : range + (read == Decimal::Number ? text : "\"" + text + "\"");
        },
        "");
}

CLI::Validator aPath() {
    return CLI::Validator(
        [](std::string& text) { return text.empty() ? "must be a path, got \"\"" : ""; }, "");
}

std::vector<std::string> renamedFlagHints(const CLI::App& app) {
    std::vector<const CLI::App*> given;  // the commands given: `map suggest` is map and suggest
    for (const CLI::App* command = &app; !command->get_subcommands().empty();)
        given.push_back(command = command->get_subcommands().front());
    std::vector<std::string> hints;
    for (const std::string& argument : app.remaining(true)) {
        const std::string flag = argument.substr(0, argument.find('='));  // --weight=5 too
        for (const RenamedFlag& renamed : kRenamedFlags) {
            if (flag != renamed.old) continue;
            const std::string now =
                renamed.key ? optionFlag(*findTakeOption(renamed.key)) : renamed.flag;
            for (const CLI::App* command : given)
                if (command->get_name() == renamed.command && command->get_option_no_throw(now)) {
                    hints.push_back(flag + " was renamed " + now);
                    break;
                }
        }
    }
    return hints;
}

void refuseUnusedExactOptions(
    const nlohmann::json& given, const SolverOptions& defaults, const std::string& where,
    const std::function<std::string(const std::string& key, const std::string& value)>& written) {
    const std::vector<const TakeOption*> unused = unusedExactOptions(given, defaults);
    if (unused.empty()) return;
    std::vector<std::string> named;
    for (const TakeOption* o : unused) {
        const std::string value = given.at(o->key).dump();
        if (where.empty())
            named.push_back(optionFlag(*o) + " " + value);
        else
            named.push_back(written ? written(o->key, value) : "\"" + o->key + "\" " + value);
    }
    SolverOptions solver = defaults;
    fromJson(given, solver, "options");
    const std::string list =
        named.size() == 1 ? named[0]
                          : joined({named.begin(), named.end() - 1}) + " and " + named.back();
    throw Error((where.empty() ? "" : where + ": ") + list +
                (named.size() == 1 ? " changes" : " change") + " nothing with the " +
                methodName(solver.method) +
                " solver: " + (named.size() == 1 ? "it applies" : "they apply") + " to " +
                (where.empty() ? "--solver exact" : "\"solver\": \"exact\"") + " only");
}
