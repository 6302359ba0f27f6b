#pragma once
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/nav/reactive/CReactiveNavigationSystem.h>

#include <string>

namespace risknav::nav {
/** @name Checks of MRPT 2.5.8's own reactive-engine INI sections
 * ([CAbstractNavigator], [CReactiveNavigationSystem], the holonomic method,
 * the score formulas, ...): values MRPT takes without a word and then
 * crashes on, asserts on every cycle or builds for minutes, refused before
 * it runs with them.
 * `layered` is the config MRPT loads (the run's keys over the engine file,
 * CLayeredConfig, or the config alone); each check throws
 * common::CBadInputError "<file>: [section] key = 'value': <rule>" for the
 * first bad key (throwBadKey()), and returns when all are good.
 * CRiskAwareReactiveNav::loadConfigFile() runs them in this order.
 * @{ */

/** Before MRPT loads `layered`: the score, assert and scalarization
 * formulas compile with MRPT's expression parser and the variables it gives
 * them (no loops, vectors of at most 1000), scores_to_normalize names
 * scores; integer keys (PTG_COUNT, a PTG's num_paths, ...) are integers in
 * range; the holonomic method and its lists, phases and thresholds;
 * motion_decider_method and each PTGn_Type are classes MRPT can make; the
 * robot shape's numbers; speedfilter_tau and CPTG_DiffDrive_alpha's
 * cte_a0v_deg / cte_a0w_deg. */
void checkEngineText(const mrpt::config::CConfigFileBase& layered);

/** After `nav` loaded `layered`: every engine key the config gives (those
 * MRPT's saveConfigFile() and each PTG's saveToConfigFile() write) has the
 * type MRPT holds it in: a number, true / false (no "# comment" after true
 * or yes), or a list of numbers (integers where MRPT writes integers), each
 * within +-1e9. Score formulas and words are left out. */
void checkEngineTypes(const mrpt::config::CConfigFileBase& layered,
                      const mrpt::nav::CReactiveNavigationSystem& nav);

/** After `nav` loaded `layered`: the values MRPT holds are in range: the
 * robot's and each PTG's speeds, the engine's distances, the holonomic
 * method's normalized distances and ratios (also secure_distance_end >
 * secure_distance_start), each PTG's refDistance, num_paths, resolution
 * (at most 1000 cells over refDistance), K != 0 and score_priority >= 0
 * (not all 0), clearance_decimated_paths <= num_paths. */
void checkEngineValues(const mrpt::config::CConfigFileBase& layered,
                       const mrpt::nav::CReactiveNavigationSystem& nav);

/** After `nav` loaded `layered`: its collision-grid PTGs together would
 * not take MRPT over ~1 min to build for a robot shape of radius
 * `shapeRadius` [m] (a model fitted to builds measured here: paths, cells,
 * reach, turning radius, robot area); else throws naming the num_paths of
 * the PTG that crosses the limit. `shapeFrom`: where the shape came from,
 * for the message ("" leaves it out). */
void checkEngineBuildTime(const mrpt::config::CConfigFileBase& layered,
                          const mrpt::nav::CReactiveNavigationSystem& nav,
                          double shapeRadius, const std::string& shapeFrom);
/** @} */
}  // namespace risknav::nav
