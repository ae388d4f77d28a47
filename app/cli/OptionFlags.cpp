#include "OptionFlags.h"

#include <cctype>

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
