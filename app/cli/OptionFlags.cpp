#include "OptionFlags.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <string>

#include "boneless/TakeOptionsJson.h"

using namespace boneless;

void addOptionFlags(CLI::App* command, nlohmann::json& given, const nlohmann::json& defaults,
                    bool solverOnly) {
    for (const TakeOption& o : takeOptions()) {
        if (solverOnly && !o.solver) continue;
        std::string help = o.doc;
        help[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(help[0])));
        if (!o.units.empty()) help += " (" + o.units + ")";
        help += " [" + defaults.at(o.key).dump() + "]";
        CLI::Option* flag = command->add_option_function<std::string>(
            optionFlag(o),
            [&given, o](const std::string& text) { given[o.key] = optionValueFromText(o, text); },
            help);
        flag->check(CLI::Validator(
            [o](std::string& text) { return checkOptionValue(o, optionValueFromText(o, text)); },
            ""));
        std::string type = o.kind == TakeOption::Kind::Integer ? "INT" : "NUMBER";
        if (o.kind == TakeOption::Kind::Choice) {
            type.clear();
            for (const std::string& c : o.choices) type += (type.empty() ? "" : "|") + c;
        }
        flag->type_name(type);
    }
}

CLI::Validator numberFrom(double low, double high, bool whole) {
    char range[64];
    std::snprintf(range, sizeof range, "must be a %snumber from %g to %g, got ",
                  whole ? "whole " : "", low, high);
    return CLI::Validator(
        [low, high, whole, range = std::string(range)](std::string& text) -> std::string {
            std::size_t used = 0;
            double x = NAN;
            try {
                x = whole ? static_cast<double>(std::stoll(text, &used)) : std::stod(text, &used);
            } catch (const std::exception&) {
                used = 0;
            }
            const bool ok =
                used == text.size() && used > 0 && std::isfinite(x) && x >= low && x <= high;
            return ok ? std::string() : range + text;
        },
        "");
}
