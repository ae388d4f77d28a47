#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

// One flag per option of core's table (TakeOptionsJson), named as its JSON key ("--fill-gaps-s"
// for "fill_gaps_s"), its help the table's line with units and default; each value given goes
// to given[key], checked as the JSON reader checks it. solverOnly: the solver's options alone.
void addOptionFlags(CLI::App* command, nlohmann::json& given, const nlohmann::json& defaults,
                    bool solverOnly);
