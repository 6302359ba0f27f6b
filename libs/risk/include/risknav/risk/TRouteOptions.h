#pragma once
#include <risknav/common/CDeclaredOptions.h>

#include <string>
#include <vector>

namespace risknav::risk {
/** A candidate route given in the config: one [RouteN] section. The evaluator
 * adds the start and goal at the ends unless the waypoints begin/end there.
 * Every key is declared once, in declare(). */
struct TRouteOptions : public common::CDeclaredOptions {
    TRouteOptions() { section = "Route1"; }
    std::string name;               ///< default: the section name
    std::vector<double> waypoints;  ///< [m] x y pairs

  protected:
    void declare(Visitor& v) override;
    /** At least one waypoint (its own message: none was the straight line). */
    void validateRules() const override;
    void onLoaded() override;
};

}  // namespace risknav::risk
