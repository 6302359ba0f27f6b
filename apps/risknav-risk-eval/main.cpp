// risknav-risk-eval: candidate routes -> risk of collision under odometry drift.
#include <risknav/common/CAppRunner.h>
#include <risknav/risk/risk_report.h>

int main(int argc, char** argv) {
    const risknav::common::TAppInfo info{"risknav-risk-eval",
                                         "Ranks routes by their integrated risk of "
                                         "collision under odometry drift (Irie et al.).",
                                         ""};
    return risknav::common::runApp(argc, argv, info, risknav::risk::runRiskEvalApp);
}
