#pragma once
#include <array>
#include <string>
#include <vector>

namespace risknav::afraid {
/** One ground-truth pose: time [s], x [m], y [m], phi [rad]. */
using TGroundTruthPose = std::array<double, 4>;

/** Reads a ground-truth file as risknav-simulate writes it: one "t x y phi"
 * line per frame (blank lines and lines starting with % or # skipped, CRLF
 * accepted), strictly: every other line must be exactly 4 finite numbers,
 * the times must increase, at most 1e7 lines. Throws common::CBadInputError
 * "file:line: what" on the first bad line. An unreadable or empty file
 * gives an empty list (the caller says which key it came from). */
std::vector<TGroundTruthPose> readGroundTruth(const std::string& file);
}  // namespace risknav::afraid
