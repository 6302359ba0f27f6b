#include <risknav/nav/CPlanFollower.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace risknav::nav {

void CPlanFollower::planUpdated(bool replanned, bool newTarget, double left, double now) {
    if (newTarget) {
        m_headBest = left, m_headwayAt = now;
        m_following.reset();
    } else if (replanned || now < m_headwayAt)
        m_headBest = left;  // (a clock gone back: a new run)
    else if (left < m_headBest - 0.1)
        m_headBest = left, m_headwayAt = now;
    if (now < m_headwayAt)
        m_headwayAt = now;
}

std::optional<CPlanFollower::TDrive> CPlanFollower::followPlan(
    const mrpt::math::TPose2D& pose, double now, const planning::CGlobalPlanner& planner,
    const TBody& body, double allowed, bool lastTarget, const TSensed& sensed) {
    const auto& o = options;
    if (!(o.plan_follow_after > 0))
        return std::nullopt;
    const double left = planner.remainingLength(pose);
    // the target's own zone: within its allowed distance MRPT marks it
    // reached; the route's end within MRPT's shape is finalApproach()'s
    const double endZone = lastTarget && o.final_approach_speed > 0
                               ? std::max(allowed, body.shapeRadius + 0.1)
                               : allowed;
    if (!m_following) {
        if (now - m_headwayAt < o.plan_follow_after || left <= endZone ||
            blockedHere(m_followBlockedAt, pose, planner.current().points.back()))
            return std::nullopt;
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
            return std::nullopt;
        }
    }
    const auto pts = sensed();
    // the plan from the robot's nearest point on
    const auto& plan = planner.current().points;
    const size_t k0 = std::min(planner.nearestIndex(pose), plan.size());
    const std::vector<mrpt::math::TPoint2D> ahead(plan.begin() + long(k0), plan.end());
    const double wMax = o.turn_rate_deg * M_PI / 180;
    TDrive d;
    d.cmd = planFollowCommand(pose, ahead, pts, body.shapeRadius - o.plan_follow_margin,
                              o.plan_follow_speed, wMax, 0.5, 1.0, bodyFloor(body));
    if (d.cmd.blocked) {
        // the follower cannot either: MRPT (and its unstick turns) again,
        // and another try after plan_follow_after
        m_following.reset();
        m_headwayAt = now;
        m_followBlockedAt = mrpt::math::TPoint2D(pose.x, pose.y);
        return std::nullopt;
    }
    char why[200];
    std::snprintf(why, sizeof(why),
                  "no headway along the global plan for %.0f s: the robot follows it "
                  "itself (%s), %.2f of %.2f m",
                  now - m_following->since + o.plan_follow_after, d.cmd.what.c_str(),
                  m_following->driven, o.plan_follow_distance);
    d.mode = "plan_follow";
    d.reason = why;
    return d;
}

bool CPlanFollower::blockedHere(std::optional<mrpt::math::TPoint2D>& at,
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

double CPlanFollower::bodyFloor(const TBody& body) const {
    return std::min(body.robotRadius + 0.02,
                    body.shapeRadius - options.plan_follow_margin);
}

std::optional<CPlanFollower::TDrive> CPlanFollower::finalApproach(
    const mrpt::math::TPose2D& pose, const mrpt::math::TPoint2D& target, double allowed,
    const TBody& body, const TSensed& sensed) {
    const auto& o = options;
    const double dist = std::hypot(target.x - pose.x, target.y - pose.y);
    const double shape = body.shapeRadius;
    if (!(o.final_approach_speed > 0) || dist <= allowed || dist > shape + 0.1 ||
        blockedHere(m_finalBlockedAt, pose, target))
        return std::nullopt;  // MRPT's (within allowed: its step marks it reached)
    const auto pts = sensed();
    // the plan follower on the straight stretch to the end (it turns in
    // place first when off it), slowly: a cycle's move (2 cm at 0.1 m/s
    // and 0.2 s) does not overshoot the allowed distance
    const std::vector<mrpt::math::TPoint2D> way{mrpt::math::TPoint2D(pose.x, pose.y),
                                                target};
    TDrive d;
    d.cmd = planFollowCommand(pose, way, pts, shape - o.plan_follow_margin,
                              o.final_approach_speed, o.turn_rate_deg * M_PI / 180, dist,
                              1.0, bodyFloor(body));
    if (d.cmd.blocked) {
        m_finalBlockedAt = mrpt::math::TPoint2D(pose.x, pose.y);
        return std::nullopt;
    }
    char why[200];
    std::snprintf(why, sizeof(why),
                  "the end %.2f m away, inside MRPT's robot shape (%.2f m): driven to "
                  "(%s)",
                  dist, shape, d.cmd.what.c_str());
    d.mode = "final_approach";
    d.reason = why;
    return d;
}
}  // namespace risknav::nav
