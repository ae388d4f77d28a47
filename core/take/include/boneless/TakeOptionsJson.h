#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "boneless/TakeSolver.h"

namespace boneless {

// One option of a take solve, as users meet it: the same key in JSON (the project's "settings",
// the sidecar's "options", batch manifests, eval's output) and, with '-' for '_', as a flag of
// `boneless-cli solve` (and of `eval` for the solver's own options). takeOptions() is the one
// table they are all written, read, checked and documented from.
struct TakeOption {
    enum class Kind { Number, Integer, Choice };
    std::string key;
    Kind kind = Kind::Number;
    std::vector<std::string> choices;  // Choice: the names it takes
    double low = 0, high = 0;          // Number, Integer: the accepted range, both included
    std::string units;                 // empty when dimensionless or a choice
    std::string doc;                   // one line
    // Keys earlier versions wrote for this option; they are read as this one.
    std::vector<std::string> oldKeys;
    bool solver = false;     // a field of SolverOptions (also an option of eval)
    bool exactOnly = false;  // read by the exact solver alone (exactOnly() adds "exact only:")
};

const std::vector<TakeOption>& takeOptions();
// "--fill-gaps-s" for "fill_gaps_s".
std::string optionFlag(const TakeOption& option);
// The option whose key or old key is `key`, or nullptr.
const TakeOption* findTakeOption(const std::string& key);

// Every option's value, under its key.
nlohmann::json toJson(const TakeSolveOptions& options);
// The solver's options only (the table's entries with `solver`).
nlohmann::json toJson(const SolverOptions& options);

// Reads the options `json` (an object) holds into `options`; absent keys keep their value, old
// keys and old method names are read as today's, and keys of options that are gone
// ("continuation_steps", "coarsest_leads", "orientation_threshold") and unknown keys are ignored.
// Throws Error "WHERE: KEY ...what is wrong" for a value of the wrong type or out of its range.
void fromJson(const nlohmann::json& json, TakeSolveOptions& options, const std::string& where);
void fromJson(const nlohmann::json& json, SolverOptions& options, const std::string& where);

// What is wrong with `value` as this option's (empty when nothing is): "must be ..., got ...".
std::string checkOptionValue(const TakeOption& option, const nlohmann::json& value);
// The value a flag's text stands for (a number, or the name), unchecked.
nlohmann::json optionValueFromText(const TakeOption& option, const std::string& text);
// What is wrong with a flag's text as this option's value, as checkOptionValue says it, a number
// as typed: "got nan" and "got -1", where the value in JSON is null and -1.0.
std::string checkOptionText(const TakeOption& option, const std::string& text);

// The options `given` sets (under their keys, read over `defaults`) that the exact solver alone
// reads, each away from its value in `defaults`, when the solver given (or else the default's) is
// not the exact one: they would change nothing, yet be recorded as options of the solve. Empty
// when there are none, or when `given` chooses the exact solver. `given` is read unchecked: check
// its values first.
std::vector<const TakeOption*> unusedExactOptions(const nlohmann::json& given,
                                                  const SolverOptions& defaults);

// `options` as their solver reads them: when it is not the exact one, the options the exact
// solver alone reads (exactOnly) back at their defaults. What a solve records of its options (a
// sidecar's "options") then says what was solved, as the command line, which refuses them without
// --solver exact, never records them changed.
TakeSolveOptions withoutUnusedExactOptions(TakeSolveOptions options);

// Throws Error "KEY ...what is wrong" naming the first option out of its range.
void validate(const TakeSolveOptions& options);

}  // namespace boneless
