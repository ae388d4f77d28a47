#include "boneless/TakeOptionsJson.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>

#include "boneless/Alignment.h"
#include "boneless/C3dReader.h"
#include "boneless/Error.h"
#include "boneless/Text.h"

namespace boneless {

using nlohmann::json;

namespace {

// A table row: what users read (TakeOption) and how it maps onto TakeSolveOptions.
struct Entry {
    TakeOption option;
    std::function<json(const TakeSolveOptions&)> get;
    std::function<void(TakeSolveOptions&, const json&)> set;
};

// Method names earlier versions wrote: "direct" (the default then, never a user's choice),
// "iterative" and "multires"/"multiresolution", methods that are gone. They solve local/global.
const char* const kOldMethodNames[] = {"direct", "iterative", "multires", "multiresolution"};

TakeOption number(std::string key, double low, double high, std::string units, std::string doc,
                  std::vector<std::string> oldKeys = {}, bool solver = false) {
    return {std::move(key), TakeOption::Kind::Number, {},    low, high, std::move(units),
            std::move(doc), std::move(oldKeys),       solver};
}

TakeOption integer(std::string key, double low, double high, std::string doc, bool solver) {
    return {std::move(key), TakeOption::Kind::Integer, {}, low, high, "", std::move(doc), {},
            solver};
}

TakeOption choice(std::string key, std::vector<std::string> choices, std::string doc,
                  std::vector<std::string> oldKeys, bool solver) {
    return {std::move(key),
            TakeOption::Kind::Choice,
            std::move(choices),
            0,
            0,
            "",
            std::move(doc),
            std::move(oldKeys),
            solver};
}

// An option the exact solver alone reads: marked, and its doc says so.
TakeOption exactOnly(TakeOption option) {
    option.exactOnly = true;
    option.doc = "exact only: " + option.doc;
    return option;
}

const std::vector<Entry>& entries() {
    using M = SolverOptions::Method;
    static const std::vector<Entry> table = {
        {choice("solver", {methodName(M::LocalGlobal), methodName(M::Exact)},
                "how each frame is found: local-global (from its own markers, fast) or exact "
                "(Gauss-Newton refining that answer: the energy's minimum, slower)",
                {"method"}, true),
         [](const TakeSolveOptions& o) { return json(methodName(o.solver.method)); },
         [](TakeSolveOptions& o, const json& v) {
             if (!parseMethod(v.get<std::string>(), o.solver.method))
                 o.solver.method = M::LocalGlobal;
         }},
        {choice("calibrate",
                {calibrateModeName(CalibrateMode::Shape), calibrateModeName(CalibrateMode::None)},
                "shape: fit the rest mesh to the actor at the calibration frame and solve every "
                "frame against it; none: solve against the rest mesh as given",
                {}, false),
         [](const TakeSolveOptions& o) { return json(calibrateModeName(o.calibrate)); },
         [](TakeSolveOptions& o, const json& v) {
             parseCalibrateMode(v.get<std::string>(), o.calibrate);
         }},
        {integer("calibration_frame", -1, 1e9,
                 "the frame (0-based) the take is aligned and the rest calibrated at; -1: the "
                 "frame closest to the rest pose among those that show every mapped marker",
                 false),
         [](const TakeSolveOptions& o) { return json(o.calibrationFrame); },
         [](TakeSolveOptions& o, const json& v) {
             o.calibrationFrame = static_cast<int>(v.get<double>());
         }},
        {choice("mesh_up", {"auto", "+x", "-x", "+y", "-y", "+z", "-z"},
                "the mesh's up axis, where the take's vertical goes; auto: the axis nearest "
                "where the alignment puts it (set it for an actor who lies or rolls in the "
                "frame the take is aligned at)",
                {}, false),
         [](const TakeSolveOptions& o) { return json(o.meshUp ? axisName(*o.meshUp) : "auto"); },
         [](TakeSolveOptions& o, const json& v) { o.meshUp = parseAxis(v.get<std::string>()); }},
        {choice(
             "take_units",
             [] {
                 std::vector<std::string> units{"file"};
                 for (const std::string& u : c3dUnitSymbols()) units.push_back(u);
                 return units;
             }(),
             "the units the take's coordinates are in; file: as its POINT:UNITS says "
             "(millimetres when it has none). Set it for a take in other units than its file "
             "says",
             {}, false),
         [](const TakeSolveOptions& o) { return json(o.takeUnits); },
         [](TakeSolveOptions& o, const json& v) { o.takeUnits = v.get<std::string>(); }},
        {number("marker_weight", 1e-9, 1e9, "",
                "how hard each marker pulls its point of the mesh, against the mesh's shape",
                {"weight"}),
         [](const TakeSolveOptions& o) { return json(o.markerWeight); },
         [](TakeSolveOptions& o, const json& v) { o.markerWeight = v.get<double>(); }},
        {number("fill_gaps_s", 0, 3600, "s",
                "a marker missing for at most this long is placed on its trajectory across the "
                "gap; longer gaps stay missing; 0 = off",
                {"fill_gaps"}),
         [](const TakeSolveOptions& o) { return json(o.fillGapSeconds); },
         [](TakeSolveOptions& o, const json& v) { o.fillGapSeconds = v.get<double>(); }},
        {number("low_pass_hz", 0, 1e5, "Hz",
                "cutoff of the zero-phase Butterworth filter on the marker trajectories; 0 = off",
                {"lowpass"}),
         [](const TakeSolveOptions& o) { return json(o.lowPassHz); },
         [](TakeSolveOptions& o, const json& v) { o.lowPassHz = v.get<double>(); }},
        {exactOnly(number("fold_guard", 0, 1e9, "",
                          "weight of the as-rigid-as-possible term that keeps flat "
                          "and thin parts from folding; 0 = the paper's energy alone",
                          {"rigidity_weight", "rigidity"}, true)),
         [](const TakeSolveOptions& o) { return json(o.solver.foldGuard); },
         [](TakeSolveOptions& o, const json& v) { o.solver.foldGuard = v.get<double>(); }},
        {exactOnly(number("orientation_guard", 0, 1e9, "",
                          "weight of the penalty on faces that shrink below a fifth "
                          "of their rest area or turn over; 0 = off",
                          {"orientation_weight"}, true)),
         [](const TakeSolveOptions& o) { return json(o.solver.orientationGuard); },
         [](TakeSolveOptions& o, const json& v) { o.solver.orientationGuard = v.get<double>(); }},
        {exactOnly(
             integer("max_iterations", 1, 1e4, "Gauss-Newton steps per frame, at most", true)),
         [](const TakeSolveOptions& o) { return json(o.solver.maxIterations); },
         [](TakeSolveOptions& o, const json& v) {
             o.solver.maxIterations = static_cast<int>(v.get<double>());
         }},
        {exactOnly(number("relative_tolerance", 0, 1, "",
                          "a frame stops once a step lowers its energy by less than "
                          "this fraction of it; 0 = it runs until max_iterations, or until no "
                          "step lowers the energy",
                          {}, true)),
         [](const TakeSolveOptions& o) { return json(o.solver.relativeTolerance); },
         [](TakeSolveOptions& o, const json& v) { o.solver.relativeTolerance = v.get<double>(); }},
    };
    return table;
}

bool isOldMethodName(const json& value) {
    return value.is_string() && std::find(std::begin(kOldMethodNames), std::end(kOldMethodNames),
                                          value.get<std::string>()) != std::end(kOldMethodNames);
}

// The value under the option's key, or else under the first of its old keys present (its key
// goes to *found); nullptr when there is none.
const json* lookUp(const json& object, const TakeOption& option, std::string* found) {
    std::vector<std::string> keys{option.key};
    keys.insert(keys.end(), option.oldKeys.begin(), option.oldKeys.end());
    for (const std::string& key : keys)
        if (auto it = object.find(key); it != object.end()) {
            *found = key;
            return &*it;
        }
    return nullptr;
}

void read(const json& object, TakeSolveOptions& options, const std::string& where,
          bool solverOnly) {
    if (!object.is_object()) throw Error(where + ": the options are not a JSON object");
    for (const Entry& e : entries()) {
        if (solverOnly && !e.option.solver) continue;
        std::string key;
        const json* value = lookUp(object, e.option, &key);
        if (!value) continue;
        if (e.option.key == "solver" && isOldMethodName(*value)) {
            options.solver.method = SolverOptions::Method::LocalGlobal;
            continue;
        }
        // An old key says what it is now: eval's "method" (boneless, arap) is another idea.
        const std::string named =
            key == e.option.key ? "\"" + key + "\""
                                : "\"" + key + "\" (the old name of \"" + e.option.key + "\")";
        if (const std::string why = checkOptionValue(e.option, *value); !why.empty())
            throw Error(where + ": " + named + " " + why);
        e.set(options, *value);
    }
}

}  // namespace

const std::vector<TakeOption>& takeOptions() {
    static const std::vector<TakeOption> options = [] {
        std::vector<TakeOption> out;
        for (const Entry& e : entries()) out.push_back(e.option);
        return out;
    }();
    return options;
}

std::string optionFlag(const TakeOption& option) {
    std::string flag = "--" + option.key;
    std::replace(flag.begin(), flag.end(), '_', '-');
    return flag;
}

const TakeOption* findTakeOption(const std::string& key) {
    for (const TakeOption& o : takeOptions())
        if (o.key == key || std::find(o.oldKeys.begin(), o.oldKeys.end(), key) != o.oldKeys.end())
            return &o;
    return nullptr;
}

json toJson(const TakeSolveOptions& options) {
    json j = json::object();
    for (const Entry& e : entries()) j[e.option.key] = e.get(options);
    return j;
}

json toJson(const SolverOptions& options) {
    TakeSolveOptions o;
    o.solver = options;
    json j = json::object();
    for (const Entry& e : entries())
        if (e.option.solver) j[e.option.key] = e.get(o);
    return j;
}

void fromJson(const json& object, TakeSolveOptions& options, const std::string& where) {
    read(object, options, where, false);
}

void fromJson(const json& object, SolverOptions& options, const std::string& where) {
    TakeSolveOptions o;
    o.solver = options;
    read(object, o, where, true);
    options = o.solver;
}

namespace {

// What is wrong with `value`, given as `got` says it.
std::string check(const TakeOption& option, const json& value, const std::string& got) {
    if (option.kind == TakeOption::Kind::Choice) {
        const auto& c = option.choices;
        if (value.is_string() && std::find(c.begin(), c.end(), value.get<std::string>()) != c.end())
            return "";
        return "must be one of " + joined(c) + ", got " + got;
    }
    const bool integer = option.kind == TakeOption::Kind::Integer;
    const std::string wanted = std::string(integer ? "a whole number" : "a number") +
                               (option.units.empty() ? "" : " (" + option.units + ")") + " from " +
                               shortNumber(option.low) + " to " + shortNumber(option.high);
    if (!value.is_number()) return "must be " + wanted + ", got " + got;
    const double x = value.get<double>();
    if (!std::isfinite(x) || x < option.low || x > option.high || (integer && x != std::floor(x)))
        return "must be " + wanted + ", got " + got;
    return "";
}

}  // namespace

std::string checkOptionValue(const TakeOption& option, const json& value) {
    return check(option, value, value.dump());
}

std::string checkOptionText(const TakeOption& option, const std::string& text) {
    double x = 0;
    if (option.kind != TakeOption::Kind::Choice && readDecimal(text, x) == Decimal::Underflow)
        return check(option, json(), text + ", " + kUnderflowNote);
    const json value = optionValueFromText(option, text);
    return check(option, value, value.is_number() ? text : value.dump());
}

json optionValueFromText(const TakeOption& option, const std::string& text) {
    if (option.kind == TakeOption::Kind::Choice) return text;
    double x = 0;
    if (readDecimal(text, x) != Decimal::Number)
        return text;  // a string: checkOptionValue says what is wrong
    return option.kind == TakeOption::Kind::Integer && x == std::floor(x) && std::abs(x) < 2e9
               ? json(static_cast<long long>(x))
               : json(x);
}

std::vector<const TakeOption*> unusedExactOptions(const json& given,
                                                  const SolverOptions& defaults) {
    TakeSolveOptions read, unchanged;
    read.solver = unchanged.solver = defaults;
    fromJson(given, read.solver, "options");
    std::vector<const TakeOption*> unused;
    if (read.solver.method == SolverOptions::Method::Exact) return unused;
    const std::vector<TakeOption>& options = takeOptions();
    for (std::size_t i = 0; i < options.size(); ++i)
        if (options[i].exactOnly && entries()[i].get(read) != entries()[i].get(unchanged))
            unused.push_back(&options[i]);
    return unused;
}

TakeSolveOptions withoutUnusedExactOptions(TakeSolveOptions options) {
    if (options.solver.method == SolverOptions::Method::Exact) return options;
    const TakeSolveOptions defaults;
    for (const Entry& e : entries())
        if (e.option.exactOnly) e.set(options, e.get(defaults));
    return options;
}

void validate(const TakeSolveOptions& options) {
    for (const Entry& e : entries())
        if (const std::string why = checkOptionValue(e.option, e.get(options)); !why.empty())
            throw Error("\"" + e.option.key + "\" " + why);
}

}  // namespace boneless
