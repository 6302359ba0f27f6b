#include <risknav/common/CBadInputError.h>
#include <risknav/common/config_read.h>
#include <risknav/common/stopping.h>
#include <risknav/nav/CAdaptiveSpeedLimiter.h>
#include <risknav/nav/CLayeredConfig.h>
#include <risknav/nav/CRiskAwareReactiveNav.h>
#include <risknav/nav/escape_heading.h>
#include <risknav/nav/plan_follow.h>
#include <risknav/sim/CSimRobotInterface.h>

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/config/CConfigFilePrefixer.h>
#include <mrpt/expr/CRuntimeCompiledExpression.h>
#include <mrpt/kinematics/CVehicleVelCmd_DiffDriven.h>
#include <mrpt/maps/CPointCloudFilterByDistance.h>
#include <mrpt/nav/holonomic/CHolonomicFullEval.h>
#include <mrpt/nav/holonomic/CHolonomicND.h>
#include <mrpt/nav/reactive/CLogFileRecord.h>
#include <mrpt/nav/reactive/CMultiObjectiveMotionOptimizerBase.h>
#include <mrpt/nav/tpspace/CPTG_DiffDrive_CollisionGridBased.h>
#include <mrpt/nav/tpspace/CPTG_DiffDrive_alpha.h>
#include <mrpt/nav/tpspace/CParameterizedTrajectoryGenerator.h>

#include <mrpt/math/TSegment2D.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/version.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

using namespace risknav::common;

namespace risknav::nav {
namespace {
const char* kSection = "CRiskAwareReactiveNav";
constexpr int kMaxUnstickTurns = 3;  // per target (see navigationStep())
/** [m] Points this far outside MRPT's robot shape count as at its edge
 * (pointsNearShape()): a laser's noise moves them in and out of it. */
constexpr double kShapeEdge = 0.03;

// A robot that does nothing: MRPT's navigator only loads a config here, but
// its destructor stops the robot it is given (not the one being driven).
class CNullRobot : public mrpt::nav::CRobot2NavInterface {
  public:
    bool getCurrentPoseAndSpeeds(mrpt::math::TPose2D&, mrpt::math::TTwist2D&,
                                 mrpt::system::TTimeStamp&, mrpt::math::TPose2D&,
                                 std::string&) override {
        return false;
    }
    bool changeSpeeds(const mrpt::kinematics::CVehicleVelCmd&) override { return false; }
    bool stop(bool) override { return true; }
    mrpt::kinematics::CVehicleVelCmd::Ptr getEmergencyStopCmd() override {
        return getStopCmd();
    }
    mrpt::kinematics::CVehicleVelCmd::Ptr getStopCmd() override {
        return std::make_shared<mrpt::kinematics::CVehicleVelCmd_DiffDriven>();
    }
    bool senseObstacles(mrpt::maps::CSimplePointsMap&,
                        mrpt::system::TTimeStamp&) override {
        return false;
    }
};

std::string lowerCase(std::string s) {
    for (auto& ch : s)
        ch = char(std::tolower(static_cast<unsigned char>(ch)));
    return s;
}

// MRPT's savers pad key names with spaces (a memory config then does not
// find them): their text read back, keys trimmed.
mrpt::config::CConfigFileMemory reparsed(const mrpt::config::CConfigFileMemory& m) {
    std::string text;
    m.getContent(text);
    return mrpt::config::CConfigFileMemory(text);
}

// A config that records the keys read from it (which of the keys MRPT's
// saveConfigFile() writes its loadConfigFile() reads back).
class CReadRecordingConfig : public mrpt::config::CConfigFileMemory {
  public:
    using mrpt::config::CConfigFileMemory::CConfigFileMemory;
    bool wasRead(const std::string& section, const std::string& key) const {
        return m_read.count(lowerCase(section + "\n" + key)) > 0;
    }

  protected:
    std::string readString(const std::string& section, const std::string& name,
                           const std::string& def,
                           bool failIfNotFound = false) const override {
        m_read.insert(lowerCase(section + "\n" + name));  // MRPT ignores case
        return mrpt::config::CConfigFileMemory::readString(section, name, def,
                                                           failIfNotFound);
    }

  private:
    mutable std::set<std::string> m_read;
};

// An engine value out of its range: exit 2 naming the key, with the text as
// written (MRPT wraps num_paths to 16 bits).
void checkEngineValue(const mrpt::config::CConfigFileBase& c,
                      const mrpt::config::CConfigFileBase& layered,
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
void checkEngineFormulas(const mrpt::config::CConfigFileBase& c,
                         const mrpt::config::CConfigFileBase& layered) {
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

// The class name without its namespace: the limiter's config section.
std::string shortName(const std::string& n) {
    const auto p = n.rfind("::");
    return p == std::string::npos ? n : n.substr(p + 2);
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
    const std::string bare = shortName(method);
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

// Values MRPT crashes or asserts on while it loads them, checked in the
// text before it does: exit 2 naming the key.
void checkEngineText(const mrpt::config::CConfigFileBase& c,
                     const mrpt::config::CConfigFileBase& layered) {
    auto check = [&](const std::string& sec, const std::string& key, double v,
                     const TRange& r) { checkEngineValue(c, layered, sec, key, v, r); };
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
    checkEngineFormulas(c, layered);
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
        const bool alpha = shortName(trim(layered.read_string(sec, k + "Type", ""))) ==
                           "CPTG_DiffDrive_alpha";
        for (const char* cte : {"cte_a0v_deg", "cte_a0w_deg"})
            if (alpha && layered.keyExists(sec, k + cte))
                check(sec, k + cte, layered.read_double(sec, k + cte, 1),
                      TRange{0, 180, true, false, "deg"});
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

// Values MRPT 2.5.8 takes without a check and then fails on at every step
// (robotMax_V_mps <= 0 or NaN: an assert each cycle, the run "completes"),
// throws on as a bare assert or bad_alloc in initialize() (a PTG's
// resolution NaN or 1e-6 m, refDistance 1e6 m), or builds for minutes (a
// PTG's num_paths 1e8): exit 2 naming the key, before MRPT builds anything.
void checkEngineValues(const mrpt::config::CConfigFileBase& c,
                       const mrpt::config::CConfigFileBase& layered,
                       const mrpt::nav::CReactiveNavigationSystem& nav) {
    auto check = [&](const std::string& sec, const std::string& key, double v,
                     const TRange& r) { checkEngineValue(c, layered, sec, key, v, r); };
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
    const std::string method = shortName(trim(ap.holonomic_method));
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
    const mrpt::config::CConfigFileMemory saved = reparsed(raw);
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

}  // namespace

void CRiskAwareReactiveNav::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s) {
    const std::string list = readString(c, s, "speed_limiters", "");
    speed_limiters.clear();
    std::istringstream in(list);
    for (std::string name; in >> name;)
        speed_limiters.push_back(name);
    turn_in_place_deg = readDouble(c, s, "turn_in_place_deg", turn_in_place_deg);
    turn_rate_deg = readDouble(c, s, "turn_rate_deg", turn_rate_deg);
    start_turn_deg = readDouble(c, s, "start_turn_deg", start_turn_deg);
    unstick_time = readDouble(c, s, "unstick_time", unstick_time);
    unstick_heading_deg = readDouble(c, s, "unstick_heading_deg", unstick_heading_deg);
    guide_lookahead = readDouble(c, s, "guide_lookahead", guide_lookahead);
    plan_follow_after = readDouble(c, s, "plan_follow_after", plan_follow_after);
    plan_follow_speed = readDouble(c, s, "plan_follow_speed", plan_follow_speed);
    plan_follow_distance = readDouble(c, s, "plan_follow_distance", plan_follow_distance);
    plan_follow_margin = readDouble(c, s, "plan_follow_margin", plan_follow_margin);
    final_approach_speed = readDouble(c, s, "final_approach_speed", final_approach_speed);
}

void CRiskAwareReactiveNav::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                                       const std::string& s) const {
    std::string list;
    for (const auto& n : speed_limiters)
        list += (list.empty() ? "" : " ") + n;
    writeKey(c, s, "speed_limiters", list);
    writeKey(c, s, "turn_in_place_deg", turn_in_place_deg);
    writeKey(c, s, "turn_rate_deg", turn_rate_deg);
    writeKey(c, s, "start_turn_deg", start_turn_deg);
    writeKey(c, s, "unstick_time", unstick_time);
    writeKey(c, s, "unstick_heading_deg", unstick_heading_deg);
    writeKey(c, s, "guide_lookahead", guide_lookahead);
    writeKey(c, s, "plan_follow_after", plan_follow_after);
    writeKey(c, s, "plan_follow_speed", plan_follow_speed);
    writeKey(c, s, "plan_follow_distance", plan_follow_distance);
    writeKey(c, s, "plan_follow_margin", plan_follow_margin);
    writeKey(c, s, "final_approach_speed", final_approach_speed);
}

void CRiskAwareReactiveNav::TOptions::validate() const {
    checkRule(speed_limiters.size() <= 16, kSection, "speed_limiters",
              std::to_string(speed_limiters.size()) + " names", "at most 16 limiters");
    // one instance per class: both would read one section, and a repeated
    // name is a typo, not a second limiter
    for (size_t i = 0; i < speed_limiters.size(); i++)
        for (size_t j = 0; j < i; j++)
            if (shortName(speed_limiters[i]) == shortName(speed_limiters[j])) {
                std::string list;
                for (const auto& n : speed_limiters)
                    list += (list.empty() ? "" : " ") + n;
                checkRule(false, kSection, "speed_limiters", list,
                          shortName(speed_limiters[i]) + " is listed twice");
            }
    checkKey(kSection, "turn_in_place_deg", turn_in_place_deg,
             TRange::closed(0, 180, "deg"));
    checkKey(kSection, "turn_rate_deg", turn_rate_deg, TRange::closed(1, 360, "deg/s"));
    checkKey(kSection, "start_turn_deg", start_turn_deg, TRange::closed(0, 180, "deg"));
    checkKey(kSection, "unstick_time", unstick_time, TRange::closed(0, 1e5, "s"));
    // below 2 s a robot driving 0.25 m/s (5 cm a 0.2 s cycle) would count as stuck
    checkRule(unstick_time == 0 || unstick_time >= 2, kSection, "unstick_time",
              numberText(unstick_time), "must be 0 (off) or at least 2 s");
    checkKey(kSection, "unstick_heading_deg", unstick_heading_deg,
             TRange::closed(1, 180, "deg"));
    checkKey(kSection, "guide_lookahead", guide_lookahead, TRange::closed(0, 20, "m"));
    checkKey(kSection, "plan_follow_after", plan_follow_after,
             TRange::closed(0, 1e5, "s"));
    checkRule(plan_follow_after == 0 || plan_follow_after >= 2, kSection,
              "plan_follow_after", numberText(plan_follow_after),
              "must be 0 (off) or at least 2 s");
    checkKey(kSection, "plan_follow_speed", plan_follow_speed,
             TRange::closed(0.02, 2, "m/s"));
    checkKey(kSection, "plan_follow_distance", plan_follow_distance,
             TRange::closed(0.1, 100, "m"));
    checkKey(kSection, "plan_follow_margin", plan_follow_margin,
             TRange::closed(0, 1, "m"));
    checkKey(kSection, "final_approach_speed", final_approach_speed,
             TRange::closed(0, 2, "m/s"));
}

CRiskAwareReactiveNav::CRiskAwareReactiveNav(mrpt::nav::CRobot2NavInterface& r,
                                             bool console, bool logFile,
                                             const std::string& logDir)
    : mrpt::nav::CReactiveNavigationSystem(r, console, logFile, logDir) {
    registerAllClasses_nav();
}

void CRiskAwareReactiveNav::navigateWaypoints(
    const mrpt::nav::TWaypointSequence& request) {
    mrpt::nav::CWaypointsNavigator::navigateWaypoints(request);
    m_requestPending = !request.waypoints.empty();
    m_planFailure.reset();  // a new navigation, not the last one's no-way
}

std::optional<CRiskAwareReactiveNav::TCurrentTarget>
CRiskAwareReactiveNav::currentTarget() const {
    return currentTarget(getWaypointNavStatus());
}

std::optional<CRiskAwareReactiveNav::TCurrentTarget> CRiskAwareReactiveNav::currentTarget(
    const mrpt::nav::TWaypointStatusSequence& st) const {
    if (getCurrentState() != NAVIGATING && !m_requestPending)
        return std::nullopt;
    for (size_t i = 0; i < st.waypoints.size(); i++)
        if (const auto& w = st.waypoints[i]; !w.reached)
            return TCurrentTarget{w.target, w.allowed_distance,
                                  i + 1 == st.waypoints.size()};
    if (m_navigationParams)
        return TCurrentTarget{
            mrpt::math::TPoint2D(m_navigationParams->target.target_coords.x,
                                 m_navigationParams->target.target_coords.y),
            m_navigationParams->target.targetAllowedDistance};
    return std::nullopt;
}

void CRiskAwareReactiveNav::navigationStep() {
    const double limitDeg = riskOptions.turn_in_place_deg;
    std::optional<mrpt::math::TPoint2D> target;
    double targetAllowed = 0;
    bool lastTarget = false;
    std::optional<mrpt::math::TPoint2D> lastStepPose;
    if (limitDeg > 0 || riskOptions.unstick_time > 0 || riskOptions.start_turn_deg > 0 ||
        riskOptions.final_approach_speed > 0 || m_planner) {
        const auto st = getWaypointNavStatus();  // one copy for both
        if (const auto ct = currentTarget(st)) {
            target = ct->point;
            targetAllowed = ct->allowedDistance;
            lastTarget = ct->last;
            if (st.last_robot_pose.x != mrpt::nav::TWaypoint::INVALID_NUM)
                lastStepPose =
                    mrpt::math::TPoint2D(st.last_robot_pose.x, st.last_robot_pose.y);
        }
    }
    if (target) {
        mrpt::math::TPose2D pose, odo;
        mrpt::math::TTwist2D vel;
        mrpt::system::TTimeStamp ts;
        std::string frame;
        // MRPT's CWaypointsNavigator counts a waypoint as reached when the
        // robot's move since its last step (the segment from that step's pose
        // to now) passes within allowed_distance of it, and marks it so in
        // its next step. Such a waypoint is not turned to: e.g. a route's
        // first waypoint at the start (its bearing is atan2 of micrometres,
        // noise) or one just passed, now behind the robot.
        auto reachedByMrpt = [&](const mrpt::math::TPose2D& p) {
            const mrpt::math::TPoint2D now(p.x, p.y);
            const mrpt::math::TSegment2D move(now, lastStepPose.value_or(now));
            return move.distance(*target) < targetAllowed;
        };
        if (m_robot.getCurrentPoseAndSpeeds(pose, vel, ts, odo, frame) &&
            !reachedByMrpt(pose)) {
            if (m_planner && !updatePlanner(pose, *target))
                return;  // no way: stopped
            if (m_planner && followPlan(pose, targetAllowed, lastTarget))
                return;  // the robot follows the plan itself this cycle
            if (lastTarget && finalApproach(pose, *target, targetAllowed))
                return;  // the end, inside MRPT's shape: driven to
            // stuck: neither 5 cm nor 5 deg of motion for unstick_time (a
            // robot MRPT dithers by +-5 deg is not caught: turned to a
            // target behind a corner, MRPT's way round it was lost); a clock
            // gone back, or a new run, starts the watch again
            const double now = mrpt::Clock::toDouble(mrpt::Clock::now());
            if (m_stillPose && now < m_stillSince)
                m_unstuck.reset(), m_guidePausedAt.reset();
            if (!m_stillPose || now < m_stillSince ||
                std::hypot(pose.x - m_stillPose->x, pose.y - m_stillPose->y) > 0.05 ||
                std::abs(mrpt::math::wrapToPi(pose.phi - m_stillPose->phi)) >
                    5 * M_PI / 180) {
                m_stillPose = pose;
                m_stillSince = now;
            }
            const double stillFor = now - m_stillSince;
            const bool stuck =
                riskOptions.unstick_time > 0 && stillFor >= riskOptions.unstick_time;
            // A robot stuck while MRPT is aimed at a guide point (e.g. frozen
            // at a slant in the entrance of a passage the way hugs) is aimed
            // straight at the waypoint again until it has moved 0.5 m or
            // has a new target (office seed 8: 45 s frozen between the desks).
            if (m_guidePausedAt &&
                (std::hypot(pose.x - m_guidePausedAt->first.x,
                            pose.y - m_guidePausedAt->first.y) > 0.5 ||
                 std::hypot(m_guidePausedAt->second.x - target->x,
                            m_guidePausedAt->second.y - target->y) > 1e-6))
                m_guidePausedAt.reset();
            if (stuck && !m_guidePausedAt && guidePoint(pose, *target))
                m_guidePausedAt = {mrpt::math::TPoint2D(pose.x, pose.y), *target};
            // turned to where MRPT is aimed: the guide point when a limiter
            // gives one (guide_lookahead), else the waypoint
            const mrpt::math::TPoint2D aim = guidePoint(pose, *target).value_or(*target);
            double bearing = mrpt::math::wrapToPi(
                std::atan2(aim.y - pose.y, aim.x - pose.x) - pose.phi);
            const double aimBearing = bearing;
            // an escape turn (below) turns to its own heading
            if (m_escapeHeading)
                bearing = mrpt::math::wrapToPi(*m_escapeHeading - pose.phi);
            double deg = std::abs(bearing) * 180 / M_PI;
            // At most kMaxUnstickTurns per target, counted again once the
            // robot got 0.5 m nearer to it than at the nearest turn: at a target
            // behind a wall, turning to it for ever would hide MRPT's own
            // verdict (its timeout approaching the target, way_seems_blocked)
            // and run to the end; one turn only left U-corridor robots
            // creeping for 100 s at a bend that a second turn gets them out of.
            const double dist = std::hypot(target->x - pose.x, target->y - pose.y);
            const bool sameTarget =
                m_unstuck && std::hypot(m_unstuck->target.x - target->x,
                                        m_unstuck->target.y - target->y) < 1e-6;
            if (!sameTarget)
                m_unstuck.reset();  // a new target (or the same one again later)
            const bool nearer = sameTarget && dist < m_unstuck->distance - 0.5;
            const bool mayUnstick =
                !sameTarget || nearer || m_unstuck->turns < kMaxUnstickTurns;
            const double unstickDeg = riskOptions.unstick_heading_deg;
            // the reference is the nearest the robot was at a turn: pushed
            // back and returning does not count as getting nearer
            auto countTurn = [&] {
                m_unstuck = sameTarget && !nearer
                                ? TUnstick{*target, std::min(dist, m_unstuck->distance),
                                           m_unstuck->turns + 1}
                                : TUnstick{*target, dist, 1};
            };
            const double startDeg = riskOptions.start_turn_deg;
            const bool standing = std::hypot(vel.vx, vel.vy) < 0.05;
            if (m_turning) {
                m_turning = deg > (m_unsticking     ? unstickDeg
                                   : m_startTurning ? startDeg
                                                    : limitDeg) /
                                      3;
                if (!m_turning)
                    m_escapeHeading.reset();
            } else if (limitDeg > 0 && deg > limitDeg) {
                m_turning = true, m_unsticking = false, m_startTurning = false;
            } else if (startDeg > 0 && deg > startDeg && standing && !m_escapeHeading) {
                m_turning = true, m_unsticking = false, m_startTurning = true;
            } else if (stuck && deg > unstickDeg && mayUnstick) {
                m_turning = true, m_unsticking = true;
                countTurn();
                m_unstickReason = "target " + numberText(std::round(deg)) +
                                  " deg off after " + numberText(std::round(stillFor)) +
                                  " s without motion";
            } else if (stuck && mayUnstick) {
                // Facing its target, yet still: obstacle points at (or in)
                // MRPT's robot shape that every forward path nears (rooms
                // M1 seed 8: stopped in a doorway 0.33 m from a post, MRPT's
                // "apparent collision" for 45 s, then its timeout). Turned
                // until its heading leads away from each of them (the first
                // step of every forward path leaves them), as near the target
                // as that allows and within turn_in_place_deg of it (MRPT's
                // forward-only PTGs must still aim at it).
                const double maxOff =
                    limitDeg > 0 ? (limitDeg - unstickDeg) * M_PI / 180 : M_PI;
                if (const auto e =
                        escapeHeading(pointsNearShape(), aimBearing, 0.0, maxOff);
                    e && std::abs(*e) * 180 / M_PI > unstickDeg / 3) {
                    m_turning = true, m_unsticking = true;
                    m_escapeHeading = pose.phi + *e;
                    bearing = *e;
                    countTurn();
                    m_unstickReason =
                        "obstacle at MRPT's robot shape after " +
                        numberText(std::round(stillFor)) +
                        " s without motion: turned away from it, " +
                        numberText(
                            std::round(std::abs(mrpt::math::wrapToPi(*e - aimBearing)) *
                                       180 / M_PI)) +
                        " deg off the target";
                }
            }
            if (m_turning) {
                mrpt::kinematics::CVehicleVelCmd_DiffDriven cmd;
                cmd.lin_vel = 0;
                cmd.ang_vel =
                    (bearing > 0 ? 1 : -1) * riskOptions.turn_rate_deg * M_PI / 180;
                m_robot.changeSpeeds(cmd);
                m_last = {};
                m_last.turning = true;
                m_last.unsticking = m_unsticking;
                m_last.reason = m_unsticking ? m_unstickReason
                                : m_startTurning
                                    ? "aim " + numberText(std::round(deg)) +
                                          " deg off a standing robot, more than "
                                          "start_turn_deg"
                                    : "target " + numberText(std::round(deg)) +
                                          " deg off, more than turn_in_place_deg";
                return;
            }
        }
    }
    m_turning = m_unsticking = m_startTurning = false;
    m_escapeHeading.reset();
    m_last = {};  // set by generate_vel_cmd() when MRPT sends a new command
    m_observeDue = !m_limiters.empty();
    try {
        mrpt::nav::CReactiveNavigationSystem::navigationStep();
    } catch (...) {
        m_observeDue = false;
        finishObserved(true);
        throw;
    }
    m_observeDue = false;
    finishObserved(false);
    m_requestPending = false;  // MRPT's step took it
    if (m_planner && target) {
        // what MRPT sensed this step (robot frame of its pose then)
        const auto& xs = m_WS_Obstacles.getPointsBufferRef_x();
        const auto& ys = m_WS_Obstacles.getPointsBufferRef_y();
        std::vector<mrpt::math::TPoint2D> pts(xs.size());
        for (size_t k = 0; k < xs.size(); k++)
            pts[k] = mrpt::math::TPoint2D(xs[k], ys[k]);
        m_planner->addSensed(m_curPoseVel.pose, pts,
                             mrpt::Clock::toDouble(mrpt::Clock::now()));
    }
}

bool CRiskAwareReactiveNav::updatePlanner(const mrpt::math::TPose2D& pose,
                                          const mrpt::math::TPoint2D& target) {
    const double now = mrpt::Clock::toDouble(mrpt::Clock::now());
    const auto ev = m_planner->update(pose, target, now);
    if (ev)  // a new plan: its own headway
        m_planBest = std::numeric_limits<double>::infinity();
    const auto& plan = m_planner->current();
    if (!plan.found) {
        m_planFailure = plan;
        m_following.reset();
        doEmergencyStop("[CGlobalPlanner] no way to the target: " + plan.reason);
        return false;
    }
    // MRPT's "not approaching the target" alarm on the way left along the
    // plan: a detour round a wall leads away from the target for a while
    const double left = m_planner->remainingLength(pose);
    if (left < m_planBest - 0.1) {
        m_planBest = left;
        m_badNavAlarm_lastMinDistTime = mrpt::Clock::now();
    }
    if (ev && ev->why == "new_target") {
        m_headBest = left, m_headwayAt = now;
        m_following.reset();
    } else if (ev || now < m_headwayAt)
        m_headBest = left;  // (a clock gone back: a new run)
    else if (left < m_headBest - 0.1)
        m_headBest = left, m_headwayAt = now;
    if (now < m_headwayAt)
        m_headwayAt = now;
    return true;
}

bool CRiskAwareReactiveNav::followPlan(const mrpt::math::TPose2D& pose, double allowed,
                                       bool lastTarget) {
    const auto& o = riskOptions;
    if (!(o.plan_follow_after > 0))
        return false;
    const double now = mrpt::Clock::toDouble(mrpt::Clock::now());
    const double left = m_planner->remainingLength(pose);
    // the target's own zone: within its allowed distance MRPT marks it
    // reached; the route's end within MRPT's shape is finalApproach()'s
    const double endZone = lastTarget && o.final_approach_speed > 0
                               ? std::max(allowed, shapeRadius() + 0.1)
                               : allowed;
    if (!m_following) {
        if (now - m_headwayAt < o.plan_follow_after || left <= endZone ||
            blockedHere(m_followBlockedAt, pose, m_planner->current().points.back()))
            return false;
        m_following = TFollowing{now, pose, 0.0};
    } else {
        auto& f = *m_following;
        f.driven += std::hypot(pose.x - f.last.x, pose.y - f.last.y);
        f.last = pose;
        // a replan does not end it: the follower takes the current plan
        // each cycle (on a built map the sensed walls replan it often)
        if (f.driven >= o.plan_follow_distance || left <= endZone) {
            m_following.reset();  // far enough: MRPT steers again
            m_headBest = left, m_headwayAt = now;
            return false;
        }
    }
    const auto pts = sensedAround(pose, now);
    // the plan from the robot's nearest point on
    const auto& plan = m_planner->current().points;
    const size_t k0 = std::min(m_planner->nearestIndex(pose), plan.size());
    const std::vector<mrpt::math::TPoint2D> ahead(plan.begin() + long(k0), plan.end());
    const double wMax = o.turn_rate_deg * M_PI / 180;
    const auto cmd =
        planFollowCommand(pose, ahead, pts, shapeRadius() - o.plan_follow_margin,
                          o.plan_follow_speed, wMax, 0.5, 1.0, bodyFloor());
    if (cmd.blocked) {
        // the follower cannot either: MRPT (and its unstick turns) again,
        // and another try after plan_follow_after
        m_following.reset();
        m_headwayAt = now;
        m_followBlockedAt = mrpt::math::TPoint2D(pose.x, pose.y);
        return false;
    }
    char why[200];
    std::snprintf(why, sizeof(why),
                  "no headway along the global plan for %.0f s: the robot follows it "
                  "itself (%s), %.2f of %.2f m",
                  now - m_following->since + o.plan_follow_after, cmd.what.c_str(),
                  m_following->driven, o.plan_follow_distance);
    sendOwnCommand(cmd, "plan_follow", why);
    return true;
}

void CRiskAwareReactiveNav::sendOwnCommand(const TFollowCommand& cmd, const char* limiter,
                                           const std::string& reason) {
    mrpt::kinematics::CVehicleVelCmd_DiffDriven vc;
    vc.lin_vel = cmd.v;
    vc.ang_vel = cmd.w;
    m_robot.changeSpeeds(vc);
    m_last = {};
    m_last.limiter = limiter;
    m_last.desired = m_last.limit = cmd.v;
    m_last.reason = reason;
}

bool CRiskAwareReactiveNav::blockedHere(std::optional<mrpt::math::TPoint2D>& at,
                                        const mrpt::math::TPose2D& pose,
                                        const mrpt::math::TPoint2D& target) {
    if (!m_blockedTarget ||
        std::hypot(m_blockedTarget->x - target.x, m_blockedTarget->y - target.y) > 1e-6) {
        m_followBlockedAt.reset(), m_finalBlockedAt.reset();
        m_blockedTarget = target;
    }
    if (at && std::hypot(pose.x - at->x, pose.y - at->y) > 0.1)
        at.reset();
    return at.has_value();
}

double CRiskAwareReactiveNav::bodyFloor() const {
    // [Robot] radius and 2 cm: the laser's range noise (1 cm) and more
    return std::min(robot.radius + 0.02, shapeRadius() - riskOptions.plan_follow_margin);
}

double CRiskAwareReactiveNav::shapeRadius() const {
    double r = 0;
    for (const auto& v : m_robotShape)
        r = std::max(r, std::hypot(v.x, v.y));
    return m_robotShape.empty() ? m_robotShapeCircularRadius : r;
}

std::vector<mrpt::math::TPoint2D> CRiskAwareReactiveNav::senseNow(
    const mrpt::math::TPose2D& pose, double now) {
    // MRPT's last scans are a cycle old, and it does not sense while the
    // navigator drives: the robot's own, robot frame now
    mrpt::maps::CSimplePointsMap sensed;
    mrpt::system::TTimeStamp ts;
    std::vector<mrpt::math::TPoint2D> pts;
    if (m_robot.senseObstacles(sensed, ts)) {
        const auto& xs = sensed.getPointsBufferRef_x();
        const auto& ys = sensed.getPointsBufferRef_y();
        pts.reserve(xs.size());
        for (size_t k = 0; k < xs.size(); k++)
            pts.emplace_back(xs[k], ys[k]);
        if (m_planner)
            m_planner->addSensed(pose, pts, now);
    }
    return pts;
}

std::vector<mrpt::math::TPoint2D> CRiskAwareReactiveNav::sensedAround(
    const mrpt::math::TPose2D& pose, double now) {
    auto pts = senseNow(pose, now);
    // and what it sensed before beside and behind it (its laser looks
    // ahead; an arc swings the shape's side round a post seen earlier)
    if (m_planner) {
        const auto before = m_planner->sensedNear(pose, shapeRadius() + 0.5);
        pts.insert(pts.end(), before.begin(), before.end());
    }
    return pts;
}

bool CRiskAwareReactiveNav::finalApproach(const mrpt::math::TPose2D& pose,
                                          const mrpt::math::TPoint2D& target,
                                          double allowed) {
    const auto& o = riskOptions;
    const double d = std::hypot(target.x - pose.x, target.y - pose.y);
    const double shape = shapeRadius();
    if (!(o.final_approach_speed > 0) || d <= allowed || d > shape + 0.1 ||
        blockedHere(m_finalBlockedAt, pose, target))
        return false;  // MRPT's (within allowed: its step marks it reached)
    const double now = mrpt::Clock::toDouble(mrpt::Clock::now());
    const auto pts = sensedAround(pose, now);
    // the plan follower on the straight stretch to the end (it turns in
    // place first when off it), slowly: a cycle's move (2 cm at 0.1 m/s
    // and 0.2 s) does not overshoot the allowed distance
    const std::vector<mrpt::math::TPoint2D> way{mrpt::math::TPoint2D(pose.x, pose.y),
                                                target};
    const auto cmd = planFollowCommand(pose, way, pts, shape - o.plan_follow_margin,
                                       o.final_approach_speed,
                                       o.turn_rate_deg * M_PI / 180, d, 1.0, bodyFloor());
    if (cmd.blocked) {
        m_finalBlockedAt = mrpt::math::TPoint2D(pose.x, pose.y);
        return false;
    }
    char why[200];
    std::snprintf(why, sizeof(why),
                  "the end %.2f m away, inside MRPT's robot shape (%.2f m): driven to "
                  "(%s)",
                  d, shape, cmd.what.c_str());
    sendOwnCommand(cmd, "final_approach", why);
    return true;
}

void CRiskAwareReactiveNav::STEP3_WSpaceToTPSpace(
    const size_t ptg_idx, std::vector<double>& out_TPObstacles,
    mrpt::nav::ClearanceDiagram& out_clearance,
    const mrpt::math::TPose2D& rel_pose_PTG_origin_wrt_sense, const bool eval_clearance) {
    observeNow(false);
    mrpt::nav::CReactiveNavigationSystem::STEP3_WSpaceToTPSpace(
        ptg_idx, out_TPObstacles, out_clearance, rel_pose_PTG_origin_wrt_sense,
        eval_clearance);
}

void CRiskAwareReactiveNav::observeNow(bool beforeSensing) {
    if (!m_observeDue)
        return;
    if (beforeSensing) {
        // A risknav world senses now the scans MRPT's sensing then takes
        // (the same scans: CSimRobotInterface::senseAhead()), so the
        // limiters start ~0.2-0.3 ms of MRPT's step earlier (its sensing
        // and its work up to the first PTG); another robot's scans exist
        // only once MRPT sensed (STEP3_WSpaceToTPSpace()).
        auto* sim = dynamic_cast<sim::CSimRobotInterface*>(&m_robot);
        if (!sim)
            return;
        sim->senseAhead();
    }
    m_observeDue = false;
    TSpeedLimitInput in = limiterInput(nullptr, 0.0);
    if (beforeSensing)
        in.obstacles = nullptr;  // MRPT's point map is still the last step's
    for (const auto& l : m_limiters)
        l->observe(in);
}

void CRiskAwareReactiveNav::finishObserved(bool quiet) {
    for (const auto& l : m_limiters) {
        try {
            l->finishObserved();
        } catch (const std::exception& e) {
            if (!quiet)
                doEmergencyStop(std::string("[CRiskAwareReactiveNav] ") + e.what());
        }
    }
}

std::vector<mrpt::math::TPoint2D> CRiskAwareReactiveNav::pointsNearShape() const {
    // MRPT's shape as a disc of its farthest vertex (or its circular radius)
    double r = 0;
    for (const auto& v : m_robotShape)
        r = std::max(r, std::hypot(v.x, v.y));
    if (m_robotShape.empty())
        r = m_robotShapeCircularRadius;
    const double reach = r + kShapeEdge;
    std::vector<mrpt::math::TPoint2D> near;
    const auto& xs = m_WS_Obstacles.getPointsBufferRef_x();
    const auto& ys = m_WS_Obstacles.getPointsBufferRef_y();
    for (size_t k = 0; k < xs.size(); k++)
        if (std::hypot(xs[k], ys[k]) <= reach)
            near.emplace_back(xs[k], ys[k]);
    return near;
}

std::optional<mrpt::math::TPoint2D> CRiskAwareReactiveNav::guidePoint(
    const mrpt::math::TPose2D& pose, const mrpt::math::TPoint2D& target) const {
    if (m_planner) {
        const auto pt = m_planner->currentTarget();
        if (pt && std::hypot(pt->x - target.x, pt->y - target.y) < 1e-9 &&
            std::hypot(target.x - pose.x, target.y - pose.y) >
                m_planner->options.lookahead)
            if (auto g = m_planner->guidePoint(pose))
                return g;
    }
    const double L = riskOptions.guide_lookahead;
    if (!(L > 0) || m_guidePausedAt ||
        std::hypot(target.x - pose.x, target.y - pose.y) <= L)
        return std::nullopt;
    for (const auto& l : m_limiters)
        if (auto g = l->guidePoint(pose, L))
            return g;
    return std::nullopt;
}

void CRiskAwareReactiveNav::performNavigationStep() {
    std::optional<mrpt::math::TPoint2D> guide;
    if (m_navigationParams && !m_navigationParams->target.targetIsRelative) {
        const auto& t = m_navigationParams->target.target_coords;
        guide = guidePoint(m_curPoseVel.pose, mrpt::math::TPoint2D(t.x, t.y));
    }
    if (!guide) {
        observeNow(true);
        mrpt::nav::CReactiveNavigationSystem::performNavigationStep();
        return;
    }
    // MRPT aims at the guide point for this step only (as its one target:
    // CWaypointsNavigator's multiple_targets, the waypoints it may head to,
    // are set aside too): its waypoint bookkeeping (reached, the timeout
    // approaching it) ran before, on the waypoint; no slow-down approaching
    // the guide point (relative speed 1)
    auto* wp = dynamic_cast<TNavigationParamsWaypoints*>(m_navigationParams.get());
    const auto saved = m_navigationParams->target;
    std::vector<TargetInfo> savedMultiple;
    m_realTarget = mrpt::math::TPoint2D(saved.target_coords.x, saved.target_coords.y);
    m_navigationParams->target.target_coords.x = guide->x;
    m_navigationParams->target.target_coords.y = guide->y;
    m_navigationParams->target.targetDesiredRelSpeed = 1.0;
    if (wp)
        savedMultiple.swap(wp->multiple_targets);
    auto restore = [&] {
        m_realTarget.reset();
        if (!m_navigationParams)
            return;
        m_navigationParams->target = saved;
        if (auto* w = dynamic_cast<TNavigationParamsWaypoints*>(m_navigationParams.get()))
            w->multiple_targets = savedMultiple;
    };
    try {
        observeNow(true);  // the waypoint as the target (m_realTarget)
        mrpt::nav::CReactiveNavigationSystem::performNavigationStep();
    } catch (...) {
        restore();
        throw;
    }
    restore();
}

void CRiskAwareReactiveNav::checkPtgBuildTime(const mrpt::config::CConfigFileBase& c,
                                              const std::string& shapeFrom) const {
    const auto check = [&](const mrpt::config::CConfigFileBase& layered) {
        // (the diff-drive PTGs take the polygon; MRPT's file also gives a
        // circle, for holonomic ones)
        double shapeRadius = m_robotShape.empty() ? m_robotShapeCircularRadius : 0.0;
        for (size_t v = 0; v < m_robotShape.size(); v++)
            shapeRadius =
                std::max(shapeRadius, std::hypot(m_robotShape[v].x, m_robotShape[v].y));
        const std::string sec = "CReactiveNavigationSystem";
        double units = 0;
        for (size_t i = 0; i < getPTG_count(); i++) {
            const auto* ptg = getPTG(i);
            if (!dynamic_cast<const mrpt::nav::CPTG_DiffDrive_CollisionGridBased*>(ptg))
                continue;
            const std::string k = "PTG" + std::to_string(i) + "_";
            const double res = layered.read_double(sec, k + "resolution", 0.05),
                         ref = ptg->getRefDistance(),
                         wDeg = std::round(ptg->getMaxAngVel() * 180 / M_PI * 1e6) / 1e6;
            units += ptgBuildUnits(ptg->getAlphaValuesCount(), res, ref,
                                   ptg->getMaxLinVel(), ptg->getMaxAngVel(), shapeRadius);
            if (units > kMaxPtgBuildUnits)
                throwBadKey(
                    layered, sec, k + "num_paths",
                    std::to_string(ptg->getAlphaValuesCount()),
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
    };
    if (m_engine)
        check(CLayeredConfig(c, *m_engine));
    else
        check(c);
}

void CRiskAwareReactiveNav::loadConfigFile(const mrpt::config::CConfigFileBase& c) {
    // MRPT 2.5.8's CPTG_DiffDrive_alpha::saveToConfigFile() writes cte_a0v
    // as cte_a0w_deg: the text read is kept for saveConfigFile()
    auto keepA0w = [this](const mrpt::config::CConfigFileBase& src) {
        m_a0wText.assign(getPTG_count(), "");
        for (size_t i = 0; i < getPTG_count(); i++)
            if (dynamic_cast<const mrpt::nav::CPTG_DiffDrive_alpha*>(getPTG(i)))
                m_a0wText[i] =
                    src.read_string("CReactiveNavigationSystem",
                                    "PTG" + std::to_string(i) + "_cte_a0w_deg", "");
    };
    if (m_engine) {
        const CLayeredConfig layered(c, *m_engine);
        checkEngineText(c, layered);
        mrpt::nav::CReactiveNavigationSystem::loadConfigFile(layered);
        checkEngineTypes(layered, *this);
        checkEngineValues(c, layered, *this);
        keepA0w(layered);
    } else {
        checkEngineText(c, c);
        mrpt::nav::CReactiveNavigationSystem::loadConfigFile(c);
        checkEngineTypes(c, *this);
        checkEngineValues(c, c, *this);
        keepA0w(c);
    }
    // (with the config's robot shape; CNavigationRun checks again with the
    // shape it gives MRPT)
    checkPtgBuildTime(c);
    loadOptions(riskOptions, c, kSection);
    loadOptions(robot, c, "Robot");
    std::vector<CSpeedLimiter::Ptr> made;
    for (const auto& name : riskOptions.speed_limiters) {
        CSpeedLimiter::Ptr l;
        try {
            l = CSpeedLimiter::Factory(name);
        } catch (const CBadInputError& e) {  // unknown: names the known ones
            throw CBadInputError(configWhere(c) + "[" + kSection +
                                 "] speed_limiters: " + e.what());
        }
        if (!c.sectionExists(shortName(name)))
            throw CBadInputError(configWhere(c) + "[" + kSection +
                                 "] speed_limiters names " + name +
                                 " but the config has no [" + shortName(name) +
                                 "] section (its options; an empty section takes the "
                                 "defaults)");
        l->loadConfig(c, shortName(name));
        // candidate speeds the robot cannot reach would be silently capped
        if (const auto* a = dynamic_cast<const CAdaptiveSpeedLimiter*>(l.get());
            a && a->options.speed.speeds.front() > robot.max_v + 1e-9)
            throwBadKey(c, shortName(name), "speeds",
                        c.read_string(shortName(name), "speeds", ""),
                        "the fastest must be at most [Robot] max_v = " +
                            numberText(robot.max_v) + " m/s");
        made.push_back(l);
    }
    m_limiters = std::move(made);
}

void CRiskAwareReactiveNav::saveConfigFile(mrpt::config::CConfigFileBase& c) const {
    // Beyond MRPT 2.5.8, whose CReactiveNavigationSystem::saveConfigFile()
    // output does not load back: it writes each section twice with its keys
    // padded by spaces (an in-memory config then does not find them), and
    // neither the PTGs (PTG<n>_Type, PTG<n>_*) nor the robot shape. Its
    // text is read back (keys trimmed, sections merged), and the PTGs and the
    // shape are added as MRPT's own loader reads them.
    mrpt::config::CConfigFileMemory raw;
    mrpt::nav::CReactiveNavigationSystem::saveConfigFile(raw);
    std::string text;
    raw.getContent(text);
    CReadRecordingConfig all(text);
    const std::string nav = "CReactiveNavigationSystem";
    all.write(nav, "PTG_COUNT", int(getPTG_count()));
    for (size_t i = 0; i < getPTG_count(); i++) {
        const auto* ptg = getPTG(i);
        const std::string prefix = "PTG" + std::to_string(i) + "_";
        all.write(nav, prefix + "Type", std::string(ptg->GetRuntimeClass()->className));
        mrpt::config::CConfigFileMemory own;
        ptg->saveToConfigFile(own, "PTG");
        const mrpt::config::CConfigFileMemory parsed = reparsed(own);
        std::vector<std::string> keys;
        parsed.getAllKeys("PTG", keys);
        for (const auto& k : keys)
            all.write(nav, prefix + k, parsed.read_string("PTG", k, ""));
        if (i < m_a0wText.size() && !m_a0wText[i].empty())
            all.write(nav, prefix + "cte_a0w_deg", m_a0wText[i]);
    }
    // MRPT 2.5.8 writes a default-constructed obstacle filter's options, not
    // those of the filter it uses
    if (const auto f = std::dynamic_pointer_cast<mrpt::maps::CPointCloudFilterByDistance>(
            m_WS_filter)) {
        mrpt::config::CConfigFileMemory own;
        f->options.saveToConfigFile(own, "CPointCloudFilterByDistance");
        copyConfigKeys(reparsed(own), all);
    }
    // MRPT reads the shape into floats: 9 digits give the same floats back
    auto joined = [](const std::vector<double>& v) {
        std::ostringstream os;
        os.precision(9);
        for (size_t i = 0; i < v.size(); i++)
            os << (i ? " " : "") << float(v[i]);
        return os.str();
    };
    if (m_robotShape.size() > 0) {
        std::vector<double> xs, ys;
        m_robotShape.getAllVertices(xs, ys);
        all.write(nav, "RobotModel_shape2D_xs", joined(xs));
        all.write(nav, "RobotModel_shape2D_ys", joined(ys));
    }
    if (m_robotShapeCircularRadius > 0)
        all.write(nav, "RobotModel_circular_shape_radius", m_robotShapeCircularRadius);
    // MRPT also writes keys it never reads (e.g. [CMultiObjectiveMotion-
    // OptimizerBase] dummy, dummy2), which a loader that rejects unknown keys
    // refuses: only the keys a fresh engine reads from it are kept.
    {
        CNullRobot nobody;
        mrpt::nav::CReactiveNavigationSystem reader(nobody, false, false);
        reader.setMinLoggingLevel(mrpt::system::LVL_ERROR);
        reader.logging_enable_console_output = false;
        const_cast<mrpt::system::CTimeLogger&>(reader.getDelaysTimeLogger()).disable();
        reader.loadConfigFile(all);
    }
    copyConfigKeys(all, c, [&](const std::string& sec, const std::string& k) {
        return !all.wasRead(sec, k);
    });
    riskOptions.saveToConfigFile(c, kSection);
    robot.saveToConfigFile(c, "Robot");
    for (size_t i = 0; i < m_limiters.size(); i++)
        m_limiters[i]->saveConfig(c, shortName(riskOptions.speed_limiters[i]));
}

TSpeedLimitInput CRiskAwareReactiveNav::limiterInput(
    const mrpt::nav::TCandidateMovementPTG* movement, double desired) const {
    TSpeedLimitInput in;
    in.robot = &robot;
    in.pose = m_curPoseVel.pose;
    in.desiredSpeed = desired;
    in.obstacles = &m_WS_Obstacles;
    in.time = mrpt::Clock::toDouble(mrpt::Clock::now());
    if (m_realTarget)
        in.target = m_realTarget;  // the waypoint, not the guide point MRPT aims at
    else if (m_navigationParams)
        in.target = mrpt::math::TPoint2D(m_navigationParams->target.target_coords.x,
                                         m_navigationParams->target.target_coords.y);
    // MRPT's chosen trajectory, sampled every ~5 cm over the stopping
    // distance at the desired speed and a margin: what the limiters judge.
    if (auto* ptg = movement ? movement->PTG : nullptr) {
        const uint16_t k = ptg->alpha2index(movement->direction);
        const size_t n = ptg->getPathStepCount(k);
        const double reach =
            stoppingDistance(desired, robot.t_delay, robot.decel) + robot.radius + 1.0;
        double last = -1;
        for (size_t i = 0; i < n; i++) {
            const double d = ptg->getPathDist(k, uint32_t(i));
            if (i + 1 < n && d - last < 0.05)
                continue;
            in.path.push_back(ptg->getPathPose(k, uint32_t(i)));
            in.pathDistance.push_back(d);
            last = d;
            if (d > reach)
                break;
        }
    }
    // The raw scans (rays, not only their end points) when the robot is a
    // risknav world: the adaptive limiter maps free space along them.
    if (const auto* sim = dynamic_cast<const sim::CSimRobotInterface*>(&m_robot)) {
        in.scan = sim->lastScans().laser.get();
        in.scan2 = sim->lastScans().range2.get();
    }
    return in;
}

double CRiskAwareReactiveNav::generate_vel_cmd(
    const mrpt::nav::TCandidateMovementPTG& in_movement,
    mrpt::kinematics::CVehicleVelCmd::Ptr& new_vel_cmd) {
    const double scale =
        mrpt::nav::CReactiveNavigationSystem::generate_vel_cmd(in_movement, new_vel_cmd);
    m_last = {};
    if (!new_vel_cmd || new_vel_cmd->getVelCmdLength() == 0)
        return scale;
    // Element 0 is the forward speed of MRPT's diff-drive and holonomic commands.
    const double desired = std::abs(new_vel_cmd->getVelCmdElement(0));
    m_last.desired = m_last.limit = desired;
    if (m_limiters.empty() || !(desired > 0))
        return scale;
    TSpeedLimitInput in = limiterInput(&in_movement, desired);
    for (size_t i = 0; i < m_limiters.size(); i++) {
        // Each limiter judges the speed the ones before it left (the
        // stopping distance of 0.2 m/s, not of MRPT's 1.1).
        in.desiredSpeed = m_last.limit;
        const TSpeedLimit l = m_limiters[i]->limit(in);
        if (l.maxSpeed < m_last.limit) {
            m_last.limit = l.maxSpeed;
            m_last.limiter = shortName(riskOptions.speed_limiters[i]);
            m_last.reason = l.reason;
        }
    }
    if (m_last.limit >= desired)
        return scale;
    const double s = std::max(0.0, m_last.limit / desired);
    auto* dd =
        dynamic_cast<mrpt::kinematics::CVehicleVelCmd_DiffDriven*>(new_vel_cmd.get());
    if (s == 0 && dd) {
        // Stopped: keep MRPT's turn, in place (a disc robot sweeps nothing
        // new), so that it can turn away from what stopped it; scaling the
        // turn too would hold it facing the obstacle for ever.
        dd->lin_vel = 0;
        return scale;
    }
    new_vel_cmd->cmdVel_scale(s);
    return scale * s;
}

void CRiskAwareReactiveNav::loggingGetWSObstaclesAndShape(
    mrpt::nav::CLogFileRecord& out) {
    mrpt::nav::CReactiveNavigationSystem::loggingGetWSObstaclesAndShape(out);
    out.values["speed_desired"] = m_last.desired;
    out.values["speed_limit"] = m_last.limit;
    out.additional_debug_msgs["speed_limiter"] =
        m_last.limiter.empty() ? "none" : m_last.limiter + ": " + m_last.reason;
    if (m_realTarget && m_navigationParams) {
        // MRPT's own record has the guide point as its target
        const auto& g = m_navigationParams->target.target_coords;
        out.values["guide_x"] = g.x;
        out.values["guide_y"] = g.y;
        out.additional_debug_msgs["guide"] =
            "aimed at (" + numberText(g.x) + ", " + numberText(g.y) +
            ") on the limiter's way to the waypoint (" + numberText(m_realTarget->x) +
            ", " + numberText(m_realTarget->y) + ")";
    }
}

}  // namespace risknav::nav
