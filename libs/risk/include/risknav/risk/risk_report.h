#pragma once
#include <risknav/common/CAppRunner.h>
#include <risknav/common/COutputDir.h>
#include <risknav/risk/CRiskEvaluator.h>

#include <nlohmann/json.hpp>

namespace risknav::risk {
/** Writes risk_table.csv (every row), cov_<route>.csv and
 * cov_<route>+<sensing>.csv (the plain row and the best row of each route),
 * paths.png, ellipses_<route>.png (and ellipses_best.png), risk_profile.png
 * into `out` (staged) and returns the summary (without the app header). */
nlohmann::json writeRiskReport(const CRiskEvaluator& ev, common::COutputDir& out);

/** The risknav-risk-eval app body. */
void runRiskEvalApp(const common::TAppContext& ctx);

}  // namespace risknav::risk
