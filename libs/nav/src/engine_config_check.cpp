// MRPT 2.5.8's reactive-engine INI, checked before and after MRPT loads it
// (engine_config_check.h): MRPT's own loaders read most of these keys with
// truncating parsers and assert on them only later, every cycle.
#include <risknav/common/config_read.h>
#include <risknav/nav/engine_config_check.h>

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/config/CConfigFilePrefixer.h>
#include <mrpt/expr/CRuntimeCompiledExpression.h>
#include <mrpt/nav/holonomic/CHolonomicFullEval.h>
#include <mrpt/nav/holonomic/CHolonomicND.h>
#include <mrpt/nav/reactive/CMultiObjectiveMotionOptimizerBase.h>
#include <mrpt/nav/tpspace/CPTG_DiffDrive_CollisionGridBased.h>
#include <mrpt/nav/tpspace/CParameterizedTrajectoryGenerator.h>

#include <mrpt/version.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <utility>
#include <vector>

using namespace risknav::common;

namespace risknav::nav {
namespace {
// An engine value out of its range: exit 2 naming the key, with the text as
// written (MRPT wraps num_paths to 16 bits).
void checkEngineValue(const mrpt::config::CConfigFileBase& layered,
                      const std::string& sec, const std::string& key, double v,
                      const TRange& r) {
    if (!r.contains(v))
        throwBadKey(layered, sec, key, layered.read_string(sec, key, numberText(v)),
                    r.describe());
}

// MRPT's list separators (CConfigFileBase::read_vector): "[1, 2]" is 1 2.
std::vector<std::string> listTokens(const std::string& t) {
    std::vector<std::string> out;
    std::string cur;
    for (const char ch : t + " ") {
        if (ch == '[' || ch == ']' || ch == ',' || ch == ' ' || ch == '\t') {
            if (!cur.empty())
                out.push_back(std::move(cur));
            cur.clear();
        } else
            cur += ch;
    }
    return out;
}

bool isInteger(const std::string& t, long& v) {
    char* end = nullptr;
    errno = 0;
    v = t.empty() ? 0 : std::strtol(t.c_str(), &end, 10);
    return !t.empty() && *end == '\0' && errno != ERANGE;
}

// An integer as a user may write one for MRPT: also "121.0" (MRPT's atoi /
// stod-and-cast read it as 121), never "2.7" or "1e2" (read as 2 and 1).
bool isIntegerText(const std::string& t, long& v) {
    const auto dot = t.find('.');
    if (dot == std::string::npos)
        return isInteger(t, v);
    return dot > 0 && t.find_first_not_of('0', dot + 1) == std::string::npos &&
           isInteger(t.substr(0, dot), v);
}

// The variables MRPT 2.5.8 gives its score and assert formulas: the
// properties CAbstractPTGBasedReactive::calc_move_candidate_scores() sets on
// each candidate movement (and, for asserts, the scores' names).
const char* const kMrptCandidateVars[] = {"WS_target_x",
                                          "WS_target_y",
                                          "clearance",
                                          "clearance_50p",
                                          "clearance_path",
                                          "clearance_path_50p",
                                          "collision_free_distance",
                                          "dist_eucl_final",
                                          "dist_eucl_min",
                                          "eta",
                                          "holo_stage_eval",
                                          "hysteresis",
                                          "is_PTG_cont",
                                          "is_slowdown",
                                          "move_cur_d",
                                          "move_k",
                                          "num_paths",
                                          "original_col_free_dist",
                                          "ptg_idx",
                                          "ptg_priority",
                                          "ref_dist",
                                          "robpose_phi",
                                          "robpose_x",
                                          "robpose_y",
                                          "target_d_norm",
                                          "target_dir",
                                          "target_k"};

// The identifiers of a formula with their offsets.
std::vector<std::pair<std::string, size_t>> identifiers(const std::string& f) {
    std::vector<std::pair<std::string, size_t>> out;
    for (size_t i = 0; i < f.size();) {
        const auto c = static_cast<unsigned char>(f[i]);
        if (!(std::isalpha(c) || c == '_')) {
            // (a number's exponent or digits are no identifier)
            if (std::isdigit(c) || c == '.')
                while (i < f.size() && (std::isalnum(static_cast<unsigned char>(f[i])) ||
                                        f[i] == '.' || f[i] == '_'))
                    i++;
            else
                i++;
            continue;
        }
        const size_t start = i;
        while (i < f.size() &&
               (std::isalnum(static_cast<unsigned char>(f[i])) || f[i] == '_'))
            i++;
        out.emplace_back(f.substr(start, i - start), start);
    }
    return out;
}

// MRPT compiles its formulas in the first navigation step and, on an error,
// stops the robot with it on every cycle of the run: they are compiled here
// first, with MRPT's own compiler and the variables it would give them, and a
// formula that does not compile is a bad key (exit 2), as MRPT's loop reads
// them (CMultiObjectiveMotionOptimizerBase::TParamsBase).
void checkEngineFormulas(const mrpt::config::CConfigFileBase& layered) {
    std::map<std::string, double> vars;
    for (const char* v : kMrptCandidateVars)
        vars[v] = 0;
    auto compiles = [&](const std::string& sec, const std::string& key,
                        const std::string& formula,
                        const std::map<std::string, double>& with) {
        // MRPT evaluates each formula for every candidate motion of every
        // cycle: a loop ran for minutes, `var v[1000000000]` took 8 GB
        const auto words = identifiers(formula);
        for (size_t w = 0; w < words.size(); w++) {
            const std::string& id = words[w].first;
            if (id == "for" || id == "while" || id == "repeat")
                throwBadKey(layered, sec, key, formula,
                            "no loops (MRPT evaluates it for every candidate motion, "
                            "every cycle)");
            // var NAME[SIZE]
            if (id != "var" || w + 1 >= words.size())
                continue;
            size_t p = words[w + 1].second + words[w + 1].first.size();
            while (p < formula.size() &&
                   std::isspace(static_cast<unsigned char>(formula[p])))
                p++;
            if (p >= formula.size() || formula[p] != '[')
                continue;
            const size_t close = formula.find(']', p);
            double size = 0;
            if (close == std::string::npos ||
                !parseNumber(trim(formula.substr(p + 1, close - p - 1)), size) ||
                !(size >= 1 && size <= 1000))
                throwBadKey(layered, sec, key, formula,
                            "a vector of 1 to 1000 elements at most (" +
                                words[w + 1].first + ")");
        }
        mrpt::expr::CRuntimeCompiledExpression e;
        try {
            e.compile(formula, with, key);
        } catch (const std::exception& ex) {
            // MRPT's message holds a stack trace: only exprtk's own words
            const std::string w = ex.what();
            const auto a = w.find("Error: `"), b = w.find('`', a + 8);
            throwBadKey(layered, sec, key, formula,
                        "does not compile in MRPT's expression parser: " +
                            (a != std::string::npos && b != std::string::npos
                                 ? w.substr(a + 8, b - a - 8)
                                 : std::string("syntax error")));
        }
    };
    const std::string base = "CMultiObjectiveMotionOptimizerBase";
    std::map<std::string, double> scores;
    for (int i = 1; i <= 1000; i++) {
        const std::string nk = "score" + std::to_string(i) + "_name",
                          fk = "score" + std::to_string(i) + "_formula";
        const std::string name = layered.read_string(base, nk, ""),
                          formula = layered.read_string(base, fk, "");
        if (name.empty() || formula.empty())
            break;  // MRPT's loader reports a half-given pair itself
        if (vars.count(name))
            throwBadKey(layered, base, nk, name,
                        "is one of MRPT's candidate variables; pick another name");
        compiles(base, fk, formula, vars);
        scores[name] = 0;
    }
    // MRPT normalizes the scores named here and skips a name it has no
    // score of without a word
    if (layered.keyExists(base, "scores_to_normalize")) {
        const std::string t = layered.read_string(base, "scores_to_normalize", "");
        // (no scoreN_name given: MRPT 2.5.8's default scores)
        const std::map<std::string, double> defaults{{"collision_free_distance", 0},
                                                     {"path_index_near_target", 0},
                                                     {"euclidean_nearness", 0},
                                                     {"hysteresis", 0},
                                                     {"clearance", 0}};
        const auto& known = scores.empty() ? defaults : scores;
        std::string names;
        for (const auto& [n, unused] : known)
            names += (names.empty() ? "" : ", ") + n;
        for (const auto& n : listTokens(t))
            if (!known.count(n))
                throwBadKey(layered, base, "scores_to_normalize", t,
                            "'" + n + "' is no score (scores: " + names + ")");
    }
    auto withScores = vars;
    withScores.insert(scores.begin(), scores.end());
    for (int i = 1; i <= 1000; i++) {
        const std::string k = "movement_assert" + std::to_string(i);
        const std::string f = layered.read_string(base, k, "");
        if (f.empty())
            break;
        compiles(base, k, f, withScores);
    }
    const std::string sc = "CMultiObjMotionOpt_Scalarization";
    if (layered.keyExists(sc, "scalar_score_formula"))
        compiles(sc, "scalar_score_formula",
                 layered.read_string(sc, "scalar_score_formula", ""), scores);
}

// `name` is a class MRPT's factory can make, derived from `base`.
bool creatableClass(const std::string& name, const mrpt::rtti::TRuntimeClassId* base) {
    const auto* cls = mrpt::rtti::findRegisteredClass(name);
    return cls && cls->derivedFrom(base) && cls->ptrCreateObject;
}

// A value up to a "# comment" or "// comment" (MRPT's files end values
// with both; its atof / atoi stop there), trimmed.
std::string uncommented(const std::string& t) {
    return trim(t.substr(0, std::min(t.find('#'), t.find("//"))));
}

// An MRPT value as its number parsers read it: trimmed, up to a "# comment"
// (MRPT's own files end values with them; its atof / atoi stop there).
std::string engineNumberText(const mrpt::config::CConfigFileBase& layered,
                             const std::string& sec, const std::string& key) {
    const std::string t = trim(layered.read_string(sec, key, ""));
    return uncommented(t);
}

// " (in <file>[ (--set)])": where a key another key's message quotes was given.
std::string givenIn(const mrpt::config::CConfigFileBase& layered, const std::string& sec,
                    const std::string& key) {
    std::string w = configWhere(layered, sec, key);
    if (w.size() >= 2 && w.compare(w.size() - 2, 2, ": ") == 0)
        w.resize(w.size() - 2);
    return w.empty() ? "" : " (in " + w + ")";
}

// The holonomic method's keys, checked in the text before MRPT loads them:
// MRPT's list reader (std::stod on each of "[], \t"-separated words) failed
// on 'abc', '#' or an empty list with the one word "stod", its asserts on a
// list's length or a threshold outside [0, 1] without the key, and
// CHolonomicFullEval's phases that index no factor, weigh 0 together or
// have a threshold of 0 or 1 passed its load and then failed every cycle
// (each an emergency stop: the run ended `navigation_error`, exit 0).
// Only the method in use is checked (an unused section may hold anything,
// as MRPT's own files do).
void checkHolonomicText(const mrpt::config::CConfigFileBase& layered) {
    const std::string abs = "CAbstractPTGBasedReactive";
    if (!layered.keyExists(abs, "holonomic_method"))
        return;  // MRPT's loader names the missing key itself
    const std::string method = trim(layered.read_string(abs, "holonomic_method", ""));
    const std::string bare = shortClassName(method);
    if (!(bare == "CHolonomicFullEval" || bare == "CHolonomicND" ||
          bare == "CHolonomicVFF") ||
        !(bare == method || method == "mrpt::nav::" + bare))
        throwBadKey(layered, abs, "holonomic_method", method,
                    "must be CHolonomicFullEval, CHolonomicND or CHolonomicVFF (MRPT's "
                    "methods; no # comment)");
    // a list of numbers as MRPT reads it, of `count` (> 0 when known) numbers
    auto list = [&](const std::string& sec, const std::string& key, bool integers,
                    size_t count) {
        const std::string t = trim(layered.read_string(sec, key, ""));
        std::vector<double> out;
        for (const auto& w : listTokens(t)) {
            long n = 0;
            double v = 0;
            if (integers ? !isIntegerText(w, n) : !parseNumber(w, v))
                throwBadKey(layered, sec, key, t,
                            std::string(integers ? "not a list of integers"
                                                 : "not a list of numbers") +
                                " ('" + clippedText(w, 40) + "')");
            out.push_back(integers ? double(n) : v);
        }
        if (out.empty() || (count > 0 && out.size() != count))
            throwBadKey(
                layered, sec, key, t,
                "must list " +
                    (count > 0 ? std::to_string(count) : std::string("1 or more")) +
                    (integers ? " integers" : " numbers") + " (" + MRPT_version_str +
                    "'s " + sec + ")");
        return out;
    };
    if (bare == "CHolonomicND") {
        const std::string sec = "CHolonomicND";
        if (layered.keyExists(sec, "factorWeights")) {
            double sum = 0;
            for (const double w :
                 list(sec, "factorWeights", false,
                      mrpt::nav::CHolonomicND::TOptions().factorWeights.size())) {
                if (!(w >= 0))
                    throwBadKey(layered, sec, "factorWeights",
                                layered.read_string(sec, "factorWeights", ""),
                                "each weight must be >= 0");
                sum += w;
            }
            // (all 0 drove the office robot 3.3 m in 20 s, against 8.7 m)
            if (!(sum > 0))
                throwBadKey(layered, sec, "factorWeights",
                            layered.read_string(sec, "factorWeights", ""),
                            "the weights must add up to more than 0");
        }
        return;
    }
    if (bare != "CHolonomicFullEval")
        return;
    const std::string sec = "CHolonomicFullEval";
    // (MRPT's defaults when the file leaves them out)
    std::vector<double> weights = mrpt::nav::CHolonomicFullEval::TOptions().factorWeights;
    const size_t nFactors = weights.size();
    if (layered.keyExists(sec, "factorWeights")) {
        weights = list(sec, "factorWeights", false, nFactors);
        for (const double w : weights)
            if (!(w >= 0))
                throwBadKey(layered, sec, "factorWeights",
                            layered.read_string(sec, "factorWeights", ""),
                            "each weight must be >= 0");
    }
    if (layered.keyExists(sec, "factorNormalizeOrNot"))
        for (const double f : list(sec, "factorNormalizeOrNot", true, nFactors))
            if (!(f == 0 || f == 1))
                throwBadKey(layered, sec, "factorNormalizeOrNot",
                            layered.read_string(sec, "factorNormalizeOrNot", ""),
                            "each must be 0 or 1");
    if (!layered.keyExists(sec, "PHASE_COUNT"))
        return;
    const std::string pc = engineNumberText(layered, sec, "PHASE_COUNT");
    long phases = 0;
    if (!isIntegerText(pc, phases) || phases < 1 || phases > 10)
        throwBadKey(layered, sec, "PHASE_COUNT", pc, "must be an integer in [1, 10]");
    for (long i = 1; i <= phases; i++) {
        const std::string fk = "PHASE" + std::to_string(i) + "_FACTORS",
                          tk = "PHASE" + std::to_string(i) + "_THRESHOLD";
        if (layered.keyExists(sec, fk)) {
            double sum = 0;
            for (const double f : list(sec, fk, true, 0)) {
                if (!(f >= 0 && f < double(weights.size())))
                    throwBadKey(layered, sec, fk, layered.read_string(sec, fk, ""),
                                "each factor must be an index into factorWeights (0.." +
                                    std::to_string(long(weights.size()) - 1) + ")");
                sum += weights[size_t(f)];
            }
            if (!(sum > 0))
                throwBadKey(
                    layered, sec, fk, layered.read_string(sec, fk, ""),
                    "its factors weigh 0 together in factorWeights = '" +
                        clippedText(trim(layered.read_string(sec, "factorWeights", "")),
                                    80) +
                        "'" + givenIn(layered, sec, "factorWeights") +
                        "; MRPT asserts on it every cycle");
        }
        if (layered.keyExists(sec, tk)) {
            const std::string t = engineNumberText(layered, sec, tk);
            double th = 0;
            if (!parseNumber(t, th) || !(th > 0 && th < 1))
                throwBadKey(layered, sec, tk, t, "must be a number in (0, 1)");
        }
    }
}

// The time MRPT 2.5.8 takes to build a collision-grid PTG (once; then it is
// read from ptg_cache_dir), in builds of its default one (121 paths, 0.05 m
// cells, refDistance 10 m, v_max / w_max = 1 m/s / 60 deg/s: ~1.7-2.9 s
// here). Fitted to 22 one-PTG builds measured on this machine (the
// C, CCS and alpha PTGs; the model within -13..+20 % of each): paths
// (n / 121)^1.5 (1,000 paths 32 s), cells (0.05 / res)^2, and the reach
// r = refDistance / 10 m with the turning radius q = (v_max / w_max) /
// (1 m/s / 60 deg/s) as e^(0.45 ln r + 0.14 ln q6 + 0.20 ln r ln q6 +
// 0.07 ln(q / q6)), q6 = min(q, 6) (slower turns than 10 deg/s add little:
// refDistance 50 m costs 2x, with w_max 10 deg/s 5x, 1 deg/s 5x, 0.001
// deg/s 8x), and the robot's area (shape radius / 0.35 m)^2 (0.5 m 2x,
// 1 m 8x). Each key's limits alone allow thousands of builds (hours); the
// PTGs together get at most kMaxPtgBuildUnits (~1 min).
constexpr double kMaxPtgBuildUnits = 32;
double ptgBuildUnits(double numPaths, double res, double refDistance, double vMax,
                     double wMaxRadps, double shapeRadius) {
    const double lr = std::log(refDistance / 10.0),
                 lqAll = std::log((vMax / wMaxRadps) * (60 * M_PI / 180)),
                 lq = std::min(lqAll, std::log(6.0));
    return std::pow(numPaths / 121.0, 1.5) * std::pow(0.05 / res, 2) *
           std::pow(std::max(shapeRadius, 0.1) / 0.35, 2) *
           std::exp(0.45 * lr + 0.14 * lq + 0.20 * lr * lq + 0.07 * (lqAll - lq));
}

}  // namespace

// Values MRPT crashes or asserts on while it loads them, checked in the
// text before it does: exit 2 naming the key.
void checkEngineText(const mrpt::config::CConfigFileBase& layered) {
    auto check = [&](const std::string& sec, const std::string& key, double v,
                     const TRange& r) { checkEngineValue(layered, sec, key, v, r); };
    // MRPT reads its integer keys with a truncating parser ('2.7', '2abc',
    // '1e308' all give a number): the text must be an integer in range
    auto strictInt = [&](const std::string& sec, const std::string& key,
                         const TRange& r) {
        if (!layered.keyExists(sec, key))
            return;
        const std::string t = engineNumberText(layered, sec, key);
        long v = 0;
        if (!isIntegerText(t, v))
            throwBadKey(layered, sec, key, t, "not an integer");
        if (!r.contains(double(v)))
            throwBadKey(layered, sec, key, t, r.describe());
    };
    checkEngineFormulas(layered);
    // (MRPT's saveConfigFile() does not write it, so checkEngineTypes()
    // cannot know it is a bool)
    if (layered.keyExists("CAbstractNavigator", "enable_time_profiler")) {
        const std::string t =
            trim(layered.read_string("CAbstractNavigator", "enable_time_profiler", ""));
        const std::string l = lowerCase(t);
        if (!(l == "true" || l == "false" || l == "1" || l == "0" || l == "yes" ||
              l == "no"))
            throwBadKey(layered, "CAbstractNavigator", "enable_time_profiler", t,
                        "must be true or false");
    }
    strictInt("CReactiveNavigationSystem", "PTG_COUNT", TRange::closed(1, 32, "PTGs"));
    strictInt("CWaypointsNavigator", "multitarget_look_ahead",
              TRange::closed(0, 100, "waypoints"));
    strictInt("CAbstractNavigator", "hysteresis_check_target_is_blocked",
              TRange::closed(1, 1000, "cycles"));
    checkHolonomicText(layered);
    // (an unknown class: MRPT's factory failed naming no key)
    const std::string abs = "CAbstractPTGBasedReactive";
    if (layered.keyExists(abs, "motion_decider_method")) {
        const std::string m = trim(layered.read_string(abs, "motion_decider_method", ""));
        if (!creatableClass(m, CLASS_ID(mrpt::nav::CMultiObjectiveMotionOptimizerBase)))
            throwBadKey(layered, abs, "motion_decider_method", m,
                        "not one of MRPT's motion deciders "
                        "(CMultiObjMotionOpt_Scalarization)");
    }
    strictInt("CPointCloudFilterByDistance", "previous_keyframes",
              TRange::closed(1, 100, "keyframes"));
    // a speed filter's time constant: NaN or < 0 crashed MRPT
    check("CAbstractPTGBasedReactive", "speedfilter_tau",
          layered.read_double("CAbstractPTGBasedReactive", "speedfilter_tau", 0),
          TRange::closed(0, 10, "s"));
    const std::string sec = "CReactiveNavigationSystem";
    // MRPT's robot shape ('abc' was a radius of 0); risknav-navigate then
    // gives MRPT its own robot's shape
    if (layered.keyExists(sec, "RobotModel_circular_shape_radius")) {
        const std::string t =
            engineNumberText(layered, sec, "RobotModel_circular_shape_radius");
        double r = 0;
        if (!parseNumber(t, r) || !(r >= 0 && r <= 100))
            throwBadKey(layered, sec, "RobotModel_circular_shape_radius", t,
                        "must be a number in [0, 100] m");
    }
    for (const char* xy : {"RobotModel_shape2D_xs", "RobotModel_shape2D_ys"})
        if (layered.keyExists(sec, xy))
            for (const auto& w : listTokens(trim(layered.read_string(sec, xy, "")))) {
                double v = 0;
                if (!parseNumber(w, v) || !(std::abs(v) <= 100))
                    throwBadKey(layered, sec, xy, trim(layered.read_string(sec, xy, "")),
                                "not a list of numbers in [-100, 100] m ('" +
                                    clippedText(w, 40) + "')");
            }
    const int n = layered.read_int(sec, "PTG_COUNT", 0);
    for (int i = 0; i < n; i++) {
        const std::string k = "PTG" + std::to_string(i) + "_";
        // a class MRPT's factory can make a PTG of (the abstract base made
        // MRPT print its own line to stderr before it failed)
        if (layered.keyExists(sec, k + "Type")) {
            const std::string type = trim(layered.read_string(sec, k + "Type", ""));
            if (!creatableClass(type,
                                CLASS_ID(mrpt::nav::CParameterizedTrajectoryGenerator)))
                throwBadKey(layered, sec, k + "Type", type,
                            "not one of MRPT's PTG classes (CPTG_DiffDrive_C, "
                            "CPTG_DiffDrive_CC, CPTG_DiffDrive_CCS, CPTG_DiffDrive_CS, "
                            "CPTG_DiffDrive_alpha, CPTG_Holo_Blend)");
        }
        // (MRPT asserts on fewer than 4 every cycle)
        strictInt(sec, k + "num_paths", TRange::closed(4, 2000, "paths"));
        // MRPT's clearance sampling (evaluate_clearance): 0 or past a path's
        // end asserted every cycle
        strictInt(sec, k + "clearance_num_points", TRange::closed(1, 100, "points"));
        strictInt(sec, k + "clearance_decimated_paths", TRange::closed(1, 2000, "paths"));
        // CPTG_DiffDrive_alpha's exp(-(alpha / cte)^2): NaN crashed MRPT, 0
        // failed its asserts every cycle (only its own keys: read for
        // another PTG, they would no longer be unknown keys)
        const bool alpha =
            shortClassName(trim(layered.read_string(sec, k + "Type", ""))) ==
            "CPTG_DiffDrive_alpha";
        for (const char* cte : {"cte_a0v_deg", "cte_a0w_deg"})
            if (alpha && layered.keyExists(sec, k + cte))
                check(sec, k + cte, layered.read_double(sec, k + cte, 1),
                      TRange{0, 180, true, false, "deg"});
    }
}

// Values MRPT 2.5.8 takes without a check and then fails on at every step
// (robotMax_V_mps <= 0 or NaN: an assert each cycle, the run "completes"),
// throws on as a bare assert or bad_alloc in initialize() (a PTG's
// resolution NaN or 1e-6 m, refDistance 1e6 m), or builds for minutes (a
// PTG's num_paths 1e8): exit 2 naming the key, before MRPT builds anything.
void checkEngineValues(const mrpt::config::CConfigFileBase& layered,
                       const mrpt::nav::CReactiveNavigationSystem& nav) {
    auto check = [&](const std::string& sec, const std::string& key, double v,
                     const TRange& r) { checkEngineValue(layered, sec, key, v, r); };
    // (1e-12 m/s or deg/s: a robot that never moved, exit 0)
    const TRange speed = TRange::closed(0.01, 100, "m/s"),
                 turn = TRange::closed(0.1, 3600, "deg/s"),
                 reach = TRange::closed(0.1, 100, "m");
    const std::string abs = "CAbstractPTGBasedReactive";
    const auto& p = nav.getCurrentRobotSpeedLimits();
    check(abs, "robotMax_V_mps", p.robotMax_V_mps, speed);
    check(abs, "robotMax_W_degps", p.robotMax_W_radps * 180 / M_PI, turn);
    // MRPT asserts end > start on every cycle (each an emergency stop) and
    // takes NaN or values outside [0, 1] (normalized TP-space distances) without a word
    const auto& ap = nav.params_abstract_ptg_navigator;
    const TRange unit = TRange::closed(0, 1, "(normalized distance)");
    check(abs, "secure_distance_start", ap.secure_distance_start, unit);
    check(abs, "secure_distance_end", ap.secure_distance_end, unit);
    if (!(ap.secure_distance_end > ap.secure_distance_start))
        throwBadKey(layered, abs, "secure_distance_end",
                    layered.read_string(abs, "secure_distance_end",
                                        numberText(ap.secure_distance_end)),
                    "must be more than secure_distance_start = " +
                        numberText(ap.secure_distance_start));
    check(abs, "min_normalized_free_space_for_ptg_continuation",
          ap.min_normalized_free_space_for_ptg_continuation, unit);
    check(abs, "ref_distance", ap.ref_distance, reach);
    check(abs, "max_distance_predicted_actual_path",
          ap.max_distance_predicted_actual_path, TRange::closed(0, 100, "m"));
    // MRPT's documented ratios in [0, 1] (by then known to be numbers)
    for (const auto& [rs, rk] : {std::pair<const char*, const char*>{
                                     "CPointCloudFilterByDistance", "max_deletion_ratio"},
                                 {"CHolonomicFullEval", "clearance_threshold_ratio"},
                                 {"CHolonomicFullEval", "gap_width_ratio_threshold"}})
        if (layered.keyExists(rs, rk))
            check(rs, rk, layered.read_double(rs, rk, 0), TRange::closed(0, 1));
    // the holonomic method's normalized distances and sector fractions, [0, 1]
    // in MRPT's documentation (TOO_CLOSE_OBSTACLE = 1.5 held the robot still
    // for the whole run, RISK_EVALUATION_DISTANCE = -1 too: exit 0); only the
    // method in use (an unused section may hold anything, as MRPT's files do)
    const std::string method = shortClassName(trim(ap.holonomic_method));
    std::vector<const char*> unitKeys;
    if (method == "CHolonomicFullEval")
        unitKeys = {"TOO_CLOSE_OBSTACLE", "TARGET_SLOW_APPROACHING_DISTANCE",
                    "OBSTACLE_SLOW_DOWN_DISTANCE"};
    else if (method == "CHolonomicND")
        unitKeys = {"WIDE_GAP_SIZE_PERCENT",
                    "MAX_SECTOR_DIST_FOR_D2_PERCENT",
                    "RISK_EVALUATION_SECTORS_PERCENT",
                    "RISK_EVALUATION_DISTANCE",
                    "TOO_CLOSE_OBSTACLE",
                    "TARGET_SLOW_APPROACHING_DISTANCE"};
    else if (method == "CHolonomicVFF")
        unitKeys = {"TARGET_SLOW_APPROACHING_DISTANCE"};
    for (const char* key : unitKeys)
        if (layered.keyExists(method, key))
            check(method, key, layered.read_double(method, key, 0), unit);
    if (method == "CHolonomicFullEval" &&
        layered.keyExists(method, "HYSTERESIS_SECTOR_COUNT"))
        check(method, "HYSTERESIS_SECTOR_COUNT",
              layered.read_double(method, "HYSTERESIS_SECTOR_COUNT", 0),
              TRange::closed(0, 1000, "sectors"));
    if (method == "CHolonomicVFF" && layered.keyExists(method, "TARGET_ATTRACTIVE_FORCE"))
        check(method, "TARGET_ATTRACTIVE_FORCE",
              layered.read_double(method, "TARGET_ATTRACTIVE_FORCE", 0),
              TRange{0, 1e6, true, false, "(MRPT's dimension-less force)"});
    check(abs, "max_dist_for_timebased_path_prediction",
          ap.max_dist_for_timebased_path_prediction, TRange::closed(0, 100, "m"));
    const std::string sec = "CReactiveNavigationSystem";
    bool anyPriority = false;
    for (size_t i = 0; i < nav.getPTG_count(); i++) {
        const auto* ptg = nav.getPTG(i);
        const std::string k = "PTG" + std::to_string(i) + "_";
        const double ref = ptg->getRefDistance();
        check(sec, k + "refDistance", ref, reach);
        check(sec, k + "num_paths", ptg->getAlphaValuesCount(),
              TRange::closed(4, 2000, "paths"));
        // the cell size of MRPT's collision grid (CPTG_DiffDrive_*; a
        // CPTG_Holo_Blend has none)
        if (dynamic_cast<const mrpt::nav::CPTG_DiffDrive_CollisionGridBased*>(ptg)) {
            const double res = layered.read_double(sec, k + "resolution", 0.05);
            check(sec, k + "resolution", res, TRange::closed(0.005, 1, "m"));
            if (ref / res > 1000)
                throwBadKey(layered, sec, k + "resolution", numberText(res),
                            "at most 1000 cells over " + k + "refDistance = " +
                                numberText(ref) + " m (MRPT's collision grid)");
        }
        check(sec, k + "v_max_mps", ptg->getMaxLinVel(), speed);
        check(sec, k + "w_max_dps", ptg->getMaxAngVel() * 180 / M_PI, turn);
        // MRPT's C, CC, CCS and CS PTGs drive at V_MAX sign(K): K = 0 is a
        // PTG that never moves
        const std::string cls = ptg->GetRuntimeClass()->className;
        if (cls.find("CPTG_DiffDrive_C") != std::string::npos &&
            layered.keyExists(sec, k + "K") && layered.read_double(sec, k + "K", 1) == 0)
            throwBadKey(layered, sec, k + "K", layered.read_string(sec, k + "K", ""),
                        "must be 1 (forward) or -1 (backward): MRPT drives at v_max "
                        "sign(K)");
        // a negative priority inverts the PTG's scores; all 0: no motion is
        // ever chosen (the robot stood still all run, exit 0)
        check(sec, k + "score_priority", ptg->getScorePriority(),
              TRange::closed(0, 1e6, "(MRPT's factor on the PTG's scores)"));
        anyPriority = anyPriority || ptg->getScorePriority() > 0;
        if (layered.keyExists(sec, k + "clearance_decimated_paths") &&
            layered.read_int(sec, k + "clearance_decimated_paths", 1) >
                int(ptg->getAlphaValuesCount()))
            throwBadKey(layered, sec, k + "clearance_decimated_paths",
                        layered.read_string(sec, k + "clearance_decimated_paths", ""),
                        "at most " + k +
                            "num_paths = " + std::to_string(ptg->getAlphaValuesCount()));
    }
    if (!anyPriority && nav.getPTG_count() > 0)
        throwBadKey(layered, sec, "PTG0_score_priority",
                    layered.read_string(sec, "PTG0_score_priority", "0"),
                    "every PTG's score_priority is 0: MRPT would never choose a motion");
}

// Every engine key the config gives, checked against the type MRPT holds it
// in: MRPT reads "abc" and "5abc" as 0 and 5 and any word as false, takes NaN
// and 1e308 (TOO_CLOSE_OBSTACLE = abc ran "completed" with 0; = 1e308 failed
// the run). The type is that of the value MRPT's own saveConfigFile() writes
// for the key, and each PTG's saveToConfigFile() for its PTGn_ keys (which
// the engine's leaves out): a number, true / false, or a list of numbers
// (of integers when MRPT writes integers, e.g. PHASE1_FACTORS; `nan`, `-`
// or `[9` in one was taken as 0 or read on), each within +-1e9. Words are
// left to MRPT.
void checkEngineTypes(const mrpt::config::CConfigFileBase& layered,
                      const mrpt::nav::CReactiveNavigationSystem& nav) {
    mrpt::config::CConfigFileMemory raw;
    nav.mrpt::nav::CReactiveNavigationSystem::saveConfigFile(raw);
    {
        // MRPT reads a PTG's keys with the prefix PTGn_ from this section
        // (CParameterizedTrajectoryGenerator::CreatePTG)
        for (size_t i = 0; i < nav.getPTG_count(); i++) {
            mrpt::config::CConfigFilePrefixer prefixed;
            prefixed.bind(raw);
            prefixed.setPrefixes("", "PTG" + std::to_string(i) + "_");
            nav.getPTG(i)->saveToConfigFile(prefixed, "CReactiveNavigationSystem");
        }
    }
    const mrpt::config::CConfigFileMemory saved = reparsedConfig(raw);
    std::vector<std::string> sections;
    saved.getAllSections(sections);
    auto isNumber = [](const std::string& t) {
        char* end = nullptr;
        // (strtod: MRPT writes what it holds, "nan" and "inf" too)
        return !t.empty() && (std::strtod(t.c_str(), &end), *end == '\0');
    };
    for (const auto& sec : sections) {
        std::vector<std::string> keys;
        saved.getAllKeys(sec, keys);
        for (const auto& key : keys) {
            // MRPT saves its scores in the order of their names, not as
            // numbered in the config: a scoreN key's saved value is another
            // score's (the formulas are compiled by checkEngineFormulas())
            const std::string lk = lowerCase(key);
            if (!layered.keyExists(sec, key) || lk.rfind("score", 0) == 0 ||
                lk.rfind("movement_assert", 0) == 0 || lk == "scalar_score_formula")
                continue;
            const std::string held = lowerCase(trim(saved.read_string(sec, key, "")));
            const std::string typed = trim(layered.read_string(sec, key, ""));
            // MRPT's own files end values with "# comments", which its
            // number parser stops at
            const std::string text = uncommented(typed);
            const std::vector<std::string> heldList = listTokens(held);
            if (held == "true" || held == "false") {
                const std::string l = lowerCase(text);
                if (!(l == "true" || l == "false" || l == "1" || l == "0" || l == "yes" ||
                      l == "no"))
                    throwBadKey(layered, sec, key, text, "must be true or false");
                // MRPT's read_bool() takes the words whole, else atoi(): it
                // reads "true # c" as false
                if ((l == "true" || l == "yes") && text != trim(typed))
                    throwBadKey(layered, sec, key, trim(typed),
                                "MRPT reads this as false: its true / yes take no # "
                                "comment (1 # comment does)");
            } else if (!heldList.empty() &&
                       std::all_of(heldList.begin(), heldList.end(), isNumber)) {
                long n = 0;
                const bool integers =
                    std::all_of(heldList.begin(), heldList.end(),
                                [&](const std::string& t) { return isInteger(t, n); });
                const std::vector<std::string> given = listTokens(text);
                // (MRPT 2.5.8's list keys that may hold one element)
                const bool list =
                    heldList.size() > 1 || lk == "factorweights" ||
                    lk == "factornormalizeornot" ||
                    (lk.size() > 8 && lk.compare(lk.size() - 8, 8, "_factors") == 0);
                if (given.empty() || (!list && given.size() != 1))
                    throwBadKey(layered, sec, key, text,
                                list ? "not a list of numbers" : "not a number");
                for (const auto& t : given) {
                    double v = 0;
                    if (integers && !isIntegerText(t, n))
                        throwBadKey(layered, sec, key, text,
                                    list ? "not a list of integers ('" + t + "')"
                                         : "not an integer");
                    if (!parseNumber(t, v))
                        throwBadKey(layered, sec, key, text,
                                    list ? "not a list of numbers ('" + t + "')"
                                         : "not a number");
                    if (!(std::abs(v) <= 1e9))
                        throwBadKey(layered, sec, key, text, "must be within +-1e9");
                }
            }
        }
    }
}

void checkEngineBuildTime(const mrpt::config::CConfigFileBase& layered,
                          const mrpt::nav::CReactiveNavigationSystem& nav,
                          double shapeRadius, const std::string& shapeFrom) {
    const std::string sec = "CReactiveNavigationSystem";
    double units = 0;
    for (size_t i = 0; i < nav.getPTG_count(); i++) {
        const auto* ptg = nav.getPTG(i);
        if (!dynamic_cast<const mrpt::nav::CPTG_DiffDrive_CollisionGridBased*>(ptg))
            continue;
        const std::string k = "PTG" + std::to_string(i) + "_";
        const double res = layered.read_double(sec, k + "resolution", 0.05),
                     ref = ptg->getRefDistance(),
                     wDeg = std::round(ptg->getMaxAngVel() * 180 / M_PI * 1e6) / 1e6;
        units += ptgBuildUnits(ptg->getAlphaValuesCount(), res, ref, ptg->getMaxLinVel(),
                               ptg->getMaxAngVel(), shapeRadius);
        if (units > kMaxPtgBuildUnits)
            throwBadKey(
                layered, sec, k + "num_paths", std::to_string(ptg->getAlphaValuesCount()),
                "with resolution = " + numberText(res) + " m, refDistance = " +
                    numberText(ref) + " m, w_max_dps = " + numberText(wDeg) +
                    " and a robot shape of radius " +
                    numberText(std::round(shapeRadius * 1000) / 1000) + " m" +
                    (shapeFrom.empty() ? "" : " (" + shapeFrom + ")") + ", " +
                    (i == 0 ? std::string("it") : "PTGs 0.." + std::to_string(i)) +
                    " would take " + numberText(std::round(units)) +
                    " times the build of MRPT's default PTG (121 paths, 0.05 m, "
                    "10 m, 60 deg/s at 1 m/s, 0.35 m), at most " +
                    numberText(kMaxPtgBuildUnits) + " in all (~1 min)");
    }
}

}  // namespace risknav::nav
