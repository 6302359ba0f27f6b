#pragma once
#include <risknav/common/CValidatedOptions.h>

#include <string>
#include <vector>

namespace risknav::risk {
/** A candidate route given in the config: one [RouteN] section. The evaluator
 * adds the start and goal at the ends unless the waypoints begin/end there. */
struct TRouteOptions : public common::CValidatedOptions {
    std::string name;                ///< default: the section name
    std::vector<double> waypoints;   ///< [m] x y pairs
    std::string section = "Route1";  ///< the section (for messages)

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                            const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& c,
                          const std::string& section) const override;
    void validate() const override;
};

}  // namespace risknav::risk
