#include <risknav/common/stopping.h>
#include <risknav/sim/CClosedLoop.h>

#include <cmath>

using mrpt::math::TPose2D;

namespace risknav::sim {
CClosedLoop::CClosedLoop(CSimWorld& w, const TOptions& o) : world(w), options(o) {}

CClosedLoop::TEnd CClosedLoop::run() {
    for (int cycle = 0;; cycle++) {
        m_cycles++;
        if (!onCycle(cycle))
            return TEnd::Controller;
        if (world.time() >= options.duration_max)
            return TEnd::Timeout;
        onCycleSteps(cycle);
        for (int k = 0; k < options.steps_per_cycle; k++) {
            onSubStep(cycle, k);
            const double t = world.time();
            const TPose2D before = world.truePose();
            world.step(options.sim_dt);
            const TPose2D now = world.truePose();
            m_travelled += std::hypot(now.x - before.x, now.y - before.y);
            monitor(options.time_as_sum ? t + options.sim_dt : world.time(), now);
            onStepped(cycle, k, now);
        }
        onCycleEnd(cycle);
    }
}

void CClosedLoop::monitor(double t, const TPose2D& now) {
    const auto& rb = world.robot;
    safety.update(t, now, rb.radius, world.agents, world.pointClearance(now.x, now.y));
    if (options.watch_corridor)
        safety.updateCorridor(
            t, now, world.speed(), rb.radius,
            common::stoppingDistance(world.speed(), rb.t_delay, rb.decel) +
                options.corridor_beta,
            rb.radius + options.corridor_lateral_margin, world.agents);
}

}  // namespace risknav::sim
