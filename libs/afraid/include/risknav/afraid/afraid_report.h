#pragma once
#include <risknav/afraid/CAfraidLearner.h>
#include <risknav/common/CAppRunner.h>
#include <risknav/common/COutputDir.h>

#include <nlohmann/json.hpp>

namespace risknav::afraid {
/** Writes the .afraid file (or <name>.partial.afraid after a partial replay),
 * afraid.png, profile.png, zones.csv, events.csv, speed_mask.pgm/.yaml (Nav2
 * Speed Filter, percent) into `out` (staged) and returns the summary. */
nlohmann::json writeAfraidReport(const CAfraidLearner& l, common::COutputDir& out);

/** The risknav-afraid-learn app body. */
void runAfraidLearnApp(const common::TAppContext& ctx);

}  // namespace risknav::afraid
