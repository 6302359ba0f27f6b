#include <risknav/afraid/afraid_level.h>
#include <risknav/afraid/afraid_zones.h>
#include <risknav/common/config_read.h>
#include <risknav/common/stopping.h>
#include <risknav/nav/CAfraidSpeedLimiter.h>

#include <mrpt/poses/CPose2D.h>

#include <cmath>
#include <cstdio>

using namespace risknav::common;

namespace risknav::nav {
IMPLEMENTS_MRPT_OBJECT(CAfraidSpeedLimiter, risknav::common::CSpeedLimiter, risknav::nav)

void CAfraidSpeedLimiter::TOptions::declare(Visitor& v) {
    // missing: validateRules() says it is required (an experiment sets it itself)
    v.path(afraid_file, "afraid_file", true,
           "risknav-afraid-learn's grid of this map (required)");
    v.number(v_max, "v_max", TRange::closed(0.01, 5, "m/s"), "speed outside the zones");
    v.number(v_safe, "v_safe", TRange::closed(0, 5, "m/s"),
             "speed when a zone lies within d_stop(v_max) + radius ahead");
    v.number(zone_threshold, "zone_threshold", TRange::closed(0, 1, "events per pass"),
             "level above which a cell is afraid");
    v.number(sample_bin, "sample_bin", TRange::closed(0.01, 10, "m"),
             "as risknav-afraid-learn's");
    krr.declare(v);  // its keys, in this section
}

void CAfraidSpeedLimiter::TOptions::validateRules() const {
    checkRule(!afraid_file.empty(), section, "afraid_file", afraid_file, "required");
    checkRule(v_safe <= v_max, section, "v_safe", numberText(v_safe), "must be <= v_max");
}

void CAfraidSpeedLimiter::loadConfig(const mrpt::config::CConfigFileBase& c,
                                     const std::string& section) {
    options.krr.section = section;
    loadOptions(options, c, section);
    // a bad file's error names the file; the key that named it goes first
    try {
        setGrid(afraid::CAfraidGrid::load(options.afraid_file));
    } catch (const CBadInputError& e) {
        throw CBadInputError(configWhere(c, section, "afraid_file") + "[" + section +
                             "] afraid_file: " + e.what());
    }
}

void CAfraidSpeedLimiter::saveConfig(mrpt::config::CConfigFileBase& c,
                                     const std::string& section) const {
    options.saveToConfigFile(c, section);
}

void CAfraidSpeedLimiter::setGrid(const afraid::CAfraidGrid& g) {
    m_grid = g;
    m_level = afraid::afraidLevel(m_grid, options.krr, options.sample_bin);
}

double CAfraidSpeedLimiter::levelAt(double x, double y) const {
    const int cx = m_grid.xToCol(x), cy = m_grid.yToRow(y);
    if (cx < 0 || cy < 0 || cx >= m_grid.sizeX() || cy >= m_grid.sizeY() ||
        m_level.empty())
        return 0;
    return m_level[size_t(cy) * size_t(m_grid.sizeX()) + size_t(cx)];
}

TSpeedLimit CAfraidSpeedLimiter::impl_limit(const TSpeedLimitInput& in) const {
    // The path ahead: the heading's straight line over the stopping distance
    // at v_max (afraidSpeedLimit samples it up to there) plus the radius.
    const double reach =
        stoppingDistance(options.v_max, in.robot->t_delay, in.robot->decel) +
        in.robot->radius;
    std::vector<mrpt::math::TPoint2D> ahead;
    if (in.path.size() >= 2) {  // the controller's path, to the world frame
        const mrpt::poses::CPose2D robotPose(in.pose);
        for (size_t i = 0; i < in.path.size(); i++) {
            const auto q = (robotPose + mrpt::poses::CPose2D(in.path[i])).asTPose();
            ahead.emplace_back(q.x, q.y);
            if (i < in.pathDistance.size() && in.pathDistance[i] > reach)
                break;
        }
    } else {
        ahead.emplace_back(in.pose.x, in.pose.y);
        ahead.emplace_back(in.pose.x + reach * std::cos(in.pose.phi),
                           in.pose.y + reach * std::sin(in.pose.phi));
    }
    const double v = afraid::afraidSpeedLimit(
        [&](double x, double y) { return levelAt(x, y); }, ahead, in.desiredSpeed,
        options.v_max, options.v_safe, options.zone_threshold, in.robot->t_delay,
        in.robot->decel);
    if (v >= in.desiredSpeed)
        return {in.desiredSpeed, ""};
    char why[96];
    if (v < options.v_max)  // v_afraid = v_safe: a zone on the path ahead
        std::snprintf(why, sizeof(why), "afraid zone within %.2f m ahead", reach);
    else  // no zone: only v_behaviour = v_max (eq. 14) below what MRPT asked
        std::snprintf(why, sizeof(why), "v_max %.2f m/s (no zone ahead)", options.v_max);
    return {v, why};
}

}  // namespace risknav::nav
