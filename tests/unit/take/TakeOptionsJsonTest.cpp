#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "boneless/Error.h"
#include "boneless/TakeOptionsJson.h"

using namespace boneless;
using nlohmann::json;

namespace {

// Every option away from its default.
TakeSolveOptions unusual(SolverOptions::Method method, CalibrateMode calibrate) {
    TakeSolveOptions o;
    o.solver.method = method;
    o.calibrate = calibrate;
    o.calibrationFrame = 17;
    o.markerWeight = 42.5;
    o.fillGapSeconds = 0.35;
    o.lowPassHz = 6.25;
    o.solver.foldGuard = 0.03;
    o.solver.orientationGuard = 55;
    o.solver.maxIterations = 7;
    o.solver.relativeTolerance = 2.5e-4;
    return o;
}

void expectSame(const TakeSolveOptions& a, const TakeSolveOptions& b) {
    EXPECT_EQ(a.solver.method, b.solver.method);
    EXPECT_EQ(a.calibrate, b.calibrate);
    EXPECT_EQ(a.calibrationFrame, b.calibrationFrame);
    EXPECT_EQ(a.markerWeight, b.markerWeight);
    EXPECT_EQ(a.fillGapSeconds, b.fillGapSeconds);
    EXPECT_EQ(a.lowPassHz, b.lowPassHz);
    EXPECT_EQ(a.solver.foldGuard, b.solver.foldGuard);
    EXPECT_EQ(a.solver.orientationGuard, b.solver.orientationGuard);
    EXPECT_EQ(a.solver.maxIterations, b.solver.maxIterations);
    EXPECT_EQ(a.solver.relativeTolerance, b.solver.relativeTolerance);
}

// The message fromJson throws for `settings`, or "" when it reads them.
std::string refusal(const json& settings) {
    TakeSolveOptions o;
    try {
        fromJson(settings, o, "p.boneless: settings");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(TakeOptionsJson, EveryMethodAndCalibrateModeSurvivesARoundTripWithEveryValueChanged) {
    for (auto method : {SolverOptions::Method::LocalGlobal, SolverOptions::Method::Exact})
        for (auto calibrate : {CalibrateMode::Shape, CalibrateMode::None}) {
            const TakeSolveOptions written = unusual(method, calibrate);
            const std::string text = toJson(written).dump();
            TakeSolveOptions read;  // defaults, all different from `written`
            fromJson(json::parse(text), read, "test");
            expectSame(read, written);
            EXPECT_EQ(toJson(read), toJson(written));
            EXPECT_NO_THROW(validate(read));
        }
    // Every option of the table is written, and nothing else.
    const json j = toJson(TakeSolveOptions{});
    EXPECT_EQ(j.size(), takeOptions().size());
    for (const TakeOption& o : takeOptions()) EXPECT_TRUE(j.contains(o.key)) << o.key;
}

TEST(TakeOptionsJson, TheSolverOptionsAloneSurviveARoundTrip) {
    const SolverOptions written = unusual(SolverOptions::Method::Exact, CalibrateMode::None).solver;
    SolverOptions read;
    fromJson(json::parse(toJson(written).dump()), read, "eval");
    EXPECT_EQ(read.method, written.method);
    EXPECT_EQ(read.foldGuard, written.foldGuard);
    EXPECT_EQ(read.orientationGuard, written.orientationGuard);
    EXPECT_EQ(read.maxIterations, written.maxIterations);
    EXPECT_EQ(read.relativeTolerance, written.relativeTolerance);
    EXPECT_FALSE(toJson(written).contains("marker_weight"));  // a take's option, not the solver's
}

// What projects and sidecars of earlier versions held (git history of ui/src/Project.cpp and
// TakeExport.cpp), and the dashed keys of the first batch manifests.
TEST(TakeOptionsJson, OldKeysAndOldMethodNamesReadAsTodays) {
    for (const char* gone : {"direct", "iterative", "multires", "multiresolution"}) {
        TakeSolveOptions o;
        o.solver.method = SolverOptions::Method::Exact;
        fromJson({{"method", gone},
                  {"marker_weight", 50},
                  {"low_pass_hz", 6},
                  {"rigidity_weight", 0.05},
                  {"orientation_weight", 20},
                  {"max_iterations", 7},
                  {"continuation_steps", 3},
                  {"coarsest_leads", true},
                  {"orientation_threshold", 0.2}},
                 o, "old.boneless");
        EXPECT_EQ(o.solver.method, SolverOptions::Method::LocalGlobal) << gone;
        EXPECT_EQ(o.markerWeight, 50);
        EXPECT_EQ(o.lowPassHz, 6);
        EXPECT_EQ(o.solver.foldGuard, 0.05);
        EXPECT_EQ(o.solver.orientationGuard, 20);
        EXPECT_EQ(o.solver.maxIterations, 7);
        EXPECT_EQ(o.calibrate, CalibrateMode::Shape);  // from before calibration: calibrate
    }
    TakeSolveOptions exact;
    fromJson({{"method", "exact"}}, exact, "old.boneless");
    EXPECT_EQ(exact.solver.method, SolverOptions::Method::Exact);

    TakeSolveOptions manifest;
    fromJson({{"weight", 20}, {"lowpass", 4}, {"fill_gaps", 0.1}, {"rigidity", 0.3}}, manifest,
             "m.json");
    EXPECT_EQ(manifest.markerWeight, 20);
    EXPECT_EQ(manifest.lowPassHz, 4);
    EXPECT_EQ(manifest.fillGapSeconds, 0.1);
    EXPECT_EQ(manifest.solver.foldGuard, 0.3);

    // Today's key wins over an old one beside it.
    TakeSolveOptions both;
    fromJson({{"fold_guard", 0.2}, {"rigidity_weight", 0.7}}, both, "p");
    EXPECT_EQ(both.solver.foldGuard, 0.2);
    EXPECT_EQ(findTakeOption("rigidity_weight")->key, "fold_guard");
    EXPECT_EQ(findTakeOption("method")->key, "solver");
    EXPECT_EQ(findTakeOption("no_such_option"), nullptr);
}

// eval's --json says "method": "boneless" or "arap"; copied into a manifest, "method" is the old
// key of "solver", and the refusal named "method" alone, as if the solver's names were eval's.
TEST(TakeOptionsJson, AnOldKeysBadValueIsRefusedNamingItsNewKey) {
    TakeSolveOptions o;
    try {
        fromJson({{"method", "arap"}}, o, "m.json: defaults");
        FAIL() << "arap is no solver";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(),
                     "m.json: defaults: \"method\" (the old name of \"solver\") must be one of "
                     "local-global, exact, got \"arap\"");
    }
}

TEST(TakeOptionsJson, ABadValueIsRefusedWithAMessageNamingTheKey) {
    for (const TakeOption& o : takeOptions()) {
        std::vector<json> bad = {"many", nullptr, json::array({1})};
        if (o.kind == TakeOption::Kind::Choice)
            bad = {"fast", 3};
        else
            bad.insert(bad.end(), {o.low - 1, o.high * 2});
        if (o.kind == TakeOption::Kind::Integer) bad.push_back(o.low + 0.5);
        for (const json& value : bad) {
            const std::string why = refusal({{o.key, value}});
            EXPECT_NE(why.find("p.boneless: settings: \"" + o.key + "\" must be"),
                      std::string::npos)
                << o.key << " = " << value << ": " << why;
            EXPECT_NE(why.find(value.dump()), std::string::npos) << why;
        }
    }
    // Through an old key, the message names the key the file holds, and today's.
    EXPECT_NE(refusal({{"rigidity_weight", -1}})
                  .find("\"rigidity_weight\" (the old name of \"fold_guard\") must be a number"),
              std::string::npos);
    EXPECT_NE(refusal({{"fill_gaps_s", -1}}).find("(s) from 0 to 3600, got -1"), std::string::npos);
    EXPECT_NE(
        refusal({{"solver", "fast"}}).find("must be one of local-global, exact, got \"fast\""),
        std::string::npos);
    EXPECT_NE(refusal(json::array()).find("not a JSON object"), std::string::npos);
    EXPECT_EQ(refusal({{"marker_weight", 1e9}, {"max_iterations", 1}, {"calibration_frame", -1}}),
              "");
}

TEST(TakeOptionsJson, ValidateNamesTheFirstOptionOutOfItsRange) {
    EXPECT_NO_THROW(validate(TakeSolveOptions{}));
    TakeSolveOptions o;
    o.fillGapSeconds = -0.5;
    o.solver.maxIterations = 0;
    try {
        validate(o);
        FAIL() << "validate accepted fill_gaps_s = -0.5";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("\"fill_gaps_s\" must be"), std::string::npos)
            << e.what();
    }
    o.fillGapSeconds = 0;
    EXPECT_THROW(validate(o), Error);  // max_iterations
}

TEST(TakeOptionsJson, EachOptionHasOneKeyOneFlagAndOneLineOfDocumentation) {
    std::set<std::string> names;
    for (const TakeOption& o : takeOptions()) {
        EXPECT_TRUE(names.insert(o.key).second) << o.key;
        for (const std::string& old : o.oldKeys) EXPECT_TRUE(names.insert(old).second) << old;
        EXPECT_FALSE(o.doc.empty()) << o.key;
        EXPECT_EQ(o.doc.find('\n'), std::string::npos) << o.key;
        std::string flag = optionFlag(o);
        std::replace(flag.begin(), flag.end(), '-', '_');
        EXPECT_EQ(flag, "__" + o.key);
        EXPECT_EQ(o.key.find('-'), std::string::npos) << o.key;
        EXPECT_EQ(o.kind == TakeOption::Kind::Choice, !o.choices.empty()) << o.key;
        // The default is within the option's range.
        EXPECT_EQ(checkOptionValue(o, toJson(TakeSolveOptions{})[o.key]), "") << o.key;
    }
}

TEST(TakeOptionsJson, AFlagsTextReadsAsTheValueTheJsonWouldHold) {
    const TakeOption& frame = *findTakeOption("calibration_frame");
    EXPECT_EQ(optionValueFromText(frame, "12"), json(12));
    EXPECT_EQ(checkOptionValue(frame, optionValueFromText(frame, "1.5")).substr(0, 7), "must be");
    EXPECT_EQ(checkOptionValue(frame, optionValueFromText(frame, "12x")).substr(0, 7), "must be");
    const TakeOption& weight = *findTakeOption("marker_weight");
    EXPECT_EQ(optionValueFromText(weight, "2.5"), json(2.5));
    EXPECT_EQ(optionValueFromText(*findTakeOption("solver"), "exact"), json("exact"));
}

// docs/options.md is the users' copy of the table: each key with its line.
TEST(TakeOptionsJson, TheOptionsPageListsEveryOptionWithItsLine) {
    std::ifstream in(std::string(BONELESS_SOURCE_DIR) + "/docs/options.md");
    ASSERT_TRUE(in) << "docs/options.md is missing";
    const std::string page((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const TakeOption& o : takeOptions()) {
        EXPECT_NE(page.find("| `" + o.key + "`"), std::string::npos) << o.key;
        EXPECT_NE(page.find(o.doc), std::string::npos) << o.key << ": " << o.doc;
        for (const std::string& old : o.oldKeys)
            EXPECT_NE(page.find("`\"" + old + "\"`"), std::string::npos) << old;
    }
}

// Local-global reads no exact-only option: as it records them, they are the defaults, and the
// others are kept; the exact solver keeps them all.
TEST(TakeOptionsJson, WithoutUnusedExactOptionsSetsOnlyTheExactOnesBackAndOnlyWithoutExact) {
    const TakeSolveOptions given = unusual(SolverOptions::Method::LocalGlobal, CalibrateMode::None);
    const json solved = toJson(withoutUnusedExactOptions(given));
    const json defaults = toJson(TakeSolveOptions{}), asGiven = toJson(given);
    for (const TakeOption& o : takeOptions())
        EXPECT_EQ(solved[o.key], o.exactOnly ? defaults[o.key] : asGiven[o.key]) << o.key;
    const TakeSolveOptions exact = unusual(SolverOptions::Method::Exact, CalibrateMode::None);
    EXPECT_EQ(toJson(withoutUnusedExactOptions(exact)), toJson(exact));
}
