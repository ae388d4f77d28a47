#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "boneless/TakeSolver.h"

// One flag per option of core's table (TakeOptionsJson), named as its JSON key ("--fill-gaps-s"
// for "fill_gaps_s"), its help the table's line with units and default; each value given goes
// to given[key], checked as the JSON reader checks it. solverOnly: the solver's options alone.
void addOptionFlags(CLI::App* command, nlohmann::json& given, const nlohmann::json& defaults,
                    bool solverOnly);

// The one flag of core's table for `key` ("mesh_up" gives --mesh-up), as addOptionFlags adds it:
// for a command that reads that option alone (map suggest's --mesh-up, the meaning solve's has).
void addOptionFlag(CLI::App* command, nlohmann::json& given, const nlohmann::json& defaults,
                   const std::string& key);

// A flag's help with its default, as the table's flags give theirs: "... (1 to 100000) [60]",
// "[10.0]", "["boneless"]" (the value as JSON writes it).
template <class T>
std::string withDefault(const std::string& help, const T& value) {
    return help + " [" + nlohmann::json(value).dump() + "]";
}

// A number from low to high, as the option tables say it: "must be a number from 0 to 100, got
// nan". CLI11's Range lets NaN through (every comparison with it is false), and inf and 1e308
// through unbounded checks. `whole` for a count: "must be a whole number from 1 to 100000, got
// 10:20", where Range's help read "INT:INT in [1 - 100000]", like a range.
CLI::Validator numberFrom(double low, double high, bool whole = false);

// A path's flag (--out, --mesh, --csv, ...): an empty one is refused naming the flag, `--out: must
// be a path, got ""`, where it failed later without it (": cannot create the folder", "unknown
// mesh file extension ''") or, as inspect's --csv, was taken as no flag at all.
CLI::Validator aPath();

// "--weight was renamed --marker-weight": a line for each flag the command line gave under the
// name it had before it took its option's key (docs/options.md), on the command that had it
// (eval's --rigidity, never solve's), and demo's --frames, now --frame-count. CLI11 alone said
// only "The following argument was not expected".
std::vector<std::string> renamedFlagHints(const CLI::App& app);

// Refuses the options of `given` that the exact solver alone reads (--fold-guard, ...), set away
// from `defaults` while the solver is not the exact one: they changed nothing, yet the sidecar
// recorded them, and batch solved a take again whenever one changed. `where` empty: they are named
// as flags, "--fold-guard 0.5 changes nothing with the local-global solver: it applies to --solver
// exact only"; else as keys of `where` (a manifest's entry), "...: it applies to "solver": "exact"
// only", each as `written` names it with its value (the entry's old name; "(from defaults)").
void refuseUnusedExactOptions(
    const nlohmann::json& given, const boneless::SolverOptions& defaults,
    const std::string& where = "",
    const std::function<std::string(const std::string& key, const std::string& value)>& written =
        nullptr);
