#include <risknav/common/config_read.h>
#include <risknav/mapping/scan_points.h>
#include <risknav/speed/CScanMatchLocalizer.h>

#include <mrpt/math/wrap2pi.h>
#include <mrpt/poses/CPose2D.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

using namespace risknav::common;
using mrpt::math::TPose2D;
using mrpt::poses::CPose2D;

namespace risknav::speed {
namespace {
/** The unit directions of the beams that ended at robot-frame points, from
 * the sensor's position (robot frame). */
std::vector<mrpt::math::TPoint2D> beamDirections(
    const std::vector<mrpt::math::TPoint2D>& pts, double sensorX, double sensorY) {
    std::vector<mrpt::math::TPoint2D> u;
    u.reserve(pts.size());
    for (const auto& p : pts) {
        const double dx = p.x - sensorX, dy = p.y - sensorY, r = std::hypot(dx, dy);
        u.emplace_back(r > 0 ? dx / r : 0.0, r > 0 ? dy / r : 0.0);
    }
    return u;
}
}  // namespace

void TScanMatchOptions::declare(Visitor& v) {
    const TRange openMetres{0, 10, true, false, "m"};
    v.integer(max_iterations, "max_iterations", TRange::closed(1, 1000),
              "Gauss-Newton iterations per scan at most");
    v.number(match_distance, "match_distance", openMetres,
             "a scan point and a map point further apart never correspond (halves on "
             "convergence down to min_match_distance)");
    v.number(min_match_distance, "min_match_distance", openMetres,
             "the correspondence threshold at convergence");
    v.number(min_goodness, "min_goodness", TRange::closed(0, 1),
             "share of the scan's points near a map line below which the match is not "
             "trusted (odometry alone that cycle)");
    v.number(max_correction, "max_correction", TRange::closed(0, 10, "m"),
             "a match further than this from the odometry prediction is refused (a wrong "
             "minimum, e.g. one rack for the next)");
    v.number(max_correction_deg, "max_correction_deg", TRange::closed(0, 180, "deg"),
             "the same for the heading");
    v.number(keyframe_distance, "keyframe_distance", TRange::closed(0, 100, "m"),
             "the scan is added to the map each time the belief has moved this far");
    v.number(keyframe_angle_deg, "keyframe_angle_deg", TRange::closed(0, 360, "deg"),
             "or turned this much");
    v.number(map_point_spacing, "map_point_spacing", TRange::closed(0.005, 1, "m"),
             "at most one map point per cell of this side (the first: the map keeps what "
             "it saw first, so that it does not drift with the robot)");
    v.number(odometry_sigma_xy, "odometry_sigma_xy", openMetres,
             "the prior's position spread per scan, plus odometry_relative x the motion");
    v.number(odometry_sigma_deg, "odometry_sigma_deg", TRange{0, 180, true, false, "deg"},
             "the prior's heading spread per scan, plus odometry_relative x (turn + "
             "motion / 1 m)");
    v.number(odometry_relative, "odometry_relative", TRange::closed(0, 10),
             "[m/m and rad/rad] the prior's growth with the odometry's motion");
    v.number(point_sigma, "point_sigma", openMetres,
             "a scan point's distance to the map's line (range noise and the map's own), "
             "as weighed against the prior");
    v.flag(estimate_range_bias, "estimate_range_bias",
           "estimate the laser's constant range offset and take it off the scans and the "
           "map");
    v.number(range_bias_sigma, "range_bias_sigma", TRange{0, 1, true, false, "m"},
             "the prior's spread of the offset's change in one match");
    v.number(range_bias_rate, "range_bias_rate", TRange{0, 1, true, false, ""},
             "share of one match's offset estimate taken into the running one");
    v.number(max_range_bias, "max_range_bias", TRange::closed(0, 1, "m"),
             "|offset| at most");
}

void TScanMatchOptions::validateRules() const {
    checkRule(min_match_distance <= match_distance, section, "min_match_distance",
              numberText(min_match_distance),
              "must be at most match_distance = " + numberText(match_distance));
}

CScanMatchLocalizer::CScanMatchLocalizer(const TScanMatchOptions& o) : m_o(o) {
    m_o.validate();
    m_map.insertionOptions.isPlanarMap = true;
}

TPose2D CScanMatchLocalizer::predict(const TPose2D& odometry) const {
    if (!m_started)
        return odometry;
    // belief + (odometry at the last scan)^-1 + odometry now
    return (CPose2D(m_pose) + (CPose2D(odometry) - CPose2D(m_odometry))).asTPose();
}

void CScanMatchLocalizer::applyRangeBiasToMap() {
    if (m_mapRangeBias == m_rangeBias)
        return;
    for (size_t j = 0; j < m_raw.size(); j++)
        m_map.setPointFast(j, float(m_raw[j].x - m_rangeBias * m_beam[j].x),
                           float(m_raw[j].y - m_rangeBias * m_beam[j].y), 0);
    m_mapRangeBias = m_rangeBias;
}

void CScanMatchLocalizer::addToMap(const std::vector<mrpt::math::TPoint2D>& pts,
                                   const std::vector<mrpt::math::TPoint2D>& dirs,
                                   const TPose2D& at) {
    // the points already in the map at the current range offset first
    applyRangeBiasToMap();
    const double c = std::cos(at.phi), s = std::sin(at.phi);
    const double inv = 1.0 / m_o.map_point_spacing;
    for (size_t i = 0; i < pts.size(); i++) {
        const auto& p = pts[i];
        const double rx = at.x + c * p.x - s * p.y;
        const double ry = at.y + s * p.x + c * p.y;
        const double ux = c * dirs[i].x - s * dirs[i].y,
                     uy = s * dirs[i].x + c * dirs[i].y;
        const double x = rx - m_rangeBias * ux, y = ry - m_rangeBias * uy;
        const int64_t ix = int64_t(std::floor(x * inv)),
                      iy = int64_t(std::floor(y * inv));
        // unsigned: shifting a negative index left is undefined
        const uint64_t key = (uint64_t(ix) << 32) ^ (uint64_t(iy) & 0xffffffffULL);
        if (m_cells.insert(key).second) {
            m_map.insertPointFast(float(x), float(y), 0);
            m_raw.emplace_back(rx, ry);
            m_beam.emplace_back(ux, uy);
        }
    }
    // insertPointFast() does not tell the map (its k-d tree) it changed
    m_map.mark_as_modified();
    // the neighbourhoods changed: every line again when asked
    m_normals.assign(m_map.size(), TNormal{});
    m_keyframe = at;
    m_stats.keyframes++;
}

const CScanMatchLocalizer::TNormal& CScanMatchLocalizer::normalOf(size_t j) const {
    TNormal& n = m_normals[j];
    if (n.known)
        return n;
    n.known = true;
    const auto& xs = m_map.getPointsBufferRef_x();
    const auto& ys = m_map.getPointsBufferRef_y();
    std::vector<size_t> idx;
    std::vector<float> d2;
    m_map.kdTreeNClosestPoint2DIdx(xs[j], ys[j], 7, idx, d2);
    // the neighbours within a few spacings: their principal axis is the
    // surface's direction, the other one its normal
    const double reach = 4 * m_o.map_point_spacing;
    double mx = 0, my = 0;
    int cnt = 0;
    for (size_t k = 0; k < idx.size(); k++)
        if (d2[k] <= reach * reach) {
            mx += xs[idx[k]];
            my += ys[idx[k]];
            cnt++;
        }
    if (cnt < 3)
        return n;
    mx /= cnt;
    my /= cnt;
    double sxx = 0, sxy = 0, syy = 0;
    for (size_t k = 0; k < idx.size(); k++)
        if (d2[k] <= reach * reach) {
            const double ex = xs[idx[k]] - mx, ey = ys[idx[k]] - my;
            sxx += ex * ex;
            sxy += ex * ey;
            syy += ey * ey;
        }
    // eigenvalues of [[sxx sxy][sxy syy]]
    const double tr = sxx + syy, det = sxx * syy - sxy * sxy;
    const double disc = std::sqrt(std::max(0.0, tr * tr / 4 - det));
    const double lMax = tr / 2 + disc, lMin = tr / 2 - disc;
    if (!(lMax > 0) || lMin > 0.1 * lMax)
        return n;  // not a line: point to point
    // the eigenvector of lMin
    double nx = sxy, ny = lMin - sxx;
    if (std::abs(nx) + std::abs(ny) < 1e-12) {
        nx = lMin - syy;
        ny = sxy;
    }
    const double len = std::hypot(nx, ny);
    if (!(len > 0))
        return n;
    n.nx = nx / len;
    n.ny = ny / len;
    n.line = true;
    return n;
}

CScanMatchLocalizer::TAlignment CScanMatchLocalizer::align(
    const std::vector<mrpt::math::TPoint2D>& pts, const TPose2D& prior,
    double priorSigmaXY, double priorSigmaPhi) const {
    return alignImpl(pts, nullptr, prior, priorSigmaXY, priorSigmaPhi);
}

CScanMatchLocalizer::TAlignment CScanMatchLocalizer::alignImpl(
    const std::vector<mrpt::math::TPoint2D>& pts,
    const std::vector<mrpt::math::TPoint2D>* dirs, const TPose2D& prior,
    double priorSigmaXY, double priorSigmaPhi) const {
    // Gauss-Newton on point-to-line distances (the map point's line, from
    // its neighbours; point to point where they form no line), a Cauchy
    // kernel, and the prediction as a weak prior (it holds the directions a
    // scan does not constrain, e.g. along a corridor). The correspondence
    // threshold halves on convergence down to min_match_distance. With the
    // beams' directions a 4th unknown: the change of the range offset, which
    // moves the scan's points and the map's along their own beams (a wall
    // seen from two places moves differently: that is what tells it).
    TAlignment a;
    TPose2D x = prior;
    double bias = 0;  // the offset's change
    const bool withBias = dirs != nullptr && dirs->size() == pts.size();
    const int n = withBias ? 4 : 3;
    double thr = m_o.match_distance;
    const auto& xs = m_map.getPointsBufferRef_x();
    const auto& ys = m_map.getPointsBufferRef_y();
    const double sigma = m_o.point_sigma;
    const double priorXY = 1 / (priorSigmaXY * priorSigmaXY),
                 priorPhi = 1 / (priorSigmaPhi * priorSigmaPhi),
                 priorBias = 1 / (m_o.range_bias_sigma * m_o.range_bias_sigma);
    size_t matched = 0;
    for (int it = 0; it < m_o.max_iterations; it++) {
        const double c = std::cos(x.phi), s = std::sin(x.phi);
        Eigen::Matrix4d H = Eigen::Matrix4d::Zero();
        Eigen::Vector4d g = Eigen::Vector4d::Zero();
        matched = 0;
        for (size_t i = 0; i < pts.size(); i++) {
            const auto& p = pts[i];
            double px = p.x, py = p.y;
            if (withBias) {
                px -= bias * (*dirs)[i].x;
                py -= bias * (*dirs)[i].y;
            }
            const double qx = x.x + c * px - s * py, qy = x.y + s * px + c * py;
            float d2 = 0;
            const size_t j = m_map.kdTreeClosestPoint2D(float(qx), float(qy), d2);
            if (d2 > thr * thr)
                continue;
            const TNormal& nj = normalOf(j);
            // only map points on a line: a point that ends what the map has
            // seen (the edge of a wall's seen part) would pull a scan that
            // sees on along the wall back to it, point to point
            if (!nj.line)
                continue;
            matched++;
            // d q / d phi
            const double dqx = -s * px - c * py, dqy = c * px - s * py;
            const double mx = xs[j] - (withBias ? bias * m_beam[j].x : 0.0),
                         my = ys[j] - (withBias ? bias * m_beam[j].y : 0.0);
            const double r = nj.nx * (qx - mx) + nj.ny * (qy - my);
            double J[4] = {nj.nx, nj.ny, nj.nx * dqx + nj.ny * dqy, 0};
            if (withBias) {
                // the scan's point moves by -bias along its beam (world
                // frame), the map's by -bias along its own
                const double ux = c * (*dirs)[i].x - s * (*dirs)[i].y,
                             uy = s * (*dirs)[i].x + c * (*dirs)[i].y;
                J[3] = nj.nx * (m_beam[j].x - ux) + nj.ny * (m_beam[j].y - uy);
            }
            const double w = 1 / (1 + r * r / (sigma * sigma));  // Cauchy
            for (int u = 0; u < n; u++) {
                g[u] += w * J[u] * r;
                for (int v = 0; v < n; v++)
                    H(u, v) += w * J[u] * J[v];
            }
        }
        if (matched < 3)
            break;
        // the priors, in units of the points' noise
        const double k2 = sigma * sigma;
        const double ep[4] = {x.x - prior.x, x.y - prior.y,
                              mrpt::math::wrapToPi(x.phi - prior.phi), bias};
        const double pw[4] = {priorXY * k2, priorXY * k2, priorPhi * k2, priorBias * k2};
        for (int u = 0; u < n; u++) {
            H(u, u) += pw[u];
            g[u] += pw[u] * ep[u];
        }
        // H is symmetric positive definite (the priors keep it so)
        Eigen::Vector4d d = Eigen::Vector4d::Zero();
        using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 4, 4>;
        const Eigen::LDLT<Small> ldlt(Small(H.topLeftCorner(n, n)));
        d.head(n) = ldlt.solve(-g.head(n));
        const bool ok = ldlt.info() == Eigen::Success && d.allFinite();
        if (!ok)
            break;
        x.x += d[0];
        x.y += d[1];
        x.phi = mrpt::math::wrapToPi(x.phi + d[2]);
        bias += d[3];
        a.iterations = it + 1;
        if (std::hypot(d[0], d[1]) < 1e-4 && std::abs(d[2]) < 1e-4 &&
            std::abs(d[3]) < 1e-4) {
            if (thr <= m_o.min_match_distance)
                break;
            thr = std::max(m_o.min_match_distance, thr / 2);
        }
    }
    a.pose = x;
    a.rangeBiasChange = bias;
    a.goodness = pts.empty() ? 0.0 : double(matched) / double(pts.size());
    return a;
}

TPose2D CScanMatchLocalizer::update(const TPose2D& odometry,
                                    const mrpt::obs::CObservation2DRangeScan* scan) {
    const TPose2D prior = predict(odometry);
    m_pose0 = m_pose;
    m_pose = prior;
    m_odometry = odometry;
    const bool first = !m_started;
    m_started = true;
    if (!scan)
        return m_pose;
    m_stats.scans++;
    // the scan's points in the robot frame (valid ranges only), and their
    // beams' directions
    const auto raw = mapping::scanToRobotFrame(*scan);
    const auto dirs = beamDirections(raw, scan->sensorPose.x(), scan->sensorPose.y());
    if (first || m_map.size() == 0) {
        addToMap(raw, dirs, m_pose);
        return m_pose;
    }
    // less the range offset the map is at
    std::vector<mrpt::math::TPoint2D> pts = raw;
    for (size_t i = 0; i < pts.size(); i++) {
        pts[i].x -= m_mapRangeBias * dirs[i].x;
        pts[i].y -= m_mapRangeBias * dirs[i].y;
    }
    if (pts.size() >= 3) {
        // the odometry's motion since the last scan: the prior's spread
        const CPose2D step = CPose2D(prior) - CPose2D(m_pose0);
        const double sXY = m_o.odometry_sigma_xy + m_o.odometry_relative * step.norm();
        // (a heading error also grows with the distance: wheels of unequal
        // size turn the robot as it drives; 1 rad per metre at the same rate)
        const double sPhi = m_o.odometry_sigma_deg * M_PI / 180 +
                            m_o.odometry_relative * (std::abs(step.phi()) + step.norm());
        const TAlignment a =
            alignImpl(pts, m_o.estimate_range_bias ? &dirs : nullptr, prior, sXY, sPhi);
        const double dxy = std::hypot(a.pose.x - prior.x, a.pose.y - prior.y);
        const double dphi = std::abs(mrpt::math::wrapToPi(a.pose.phi - prior.phi));
        m_stats.lastGoodness = a.goodness;
        if (a.goodness >= m_o.min_goodness && dxy <= m_o.max_correction &&
            dphi <= m_o.max_correction_deg * M_PI / 180) {
            m_pose = a.pose;
            m_stats.accepted++;
            m_stats.lastCorrection = dxy;
            // the offset is the sensor's: the running estimate moves a share
            // of the way to this match's (the map's offset and its change)
            if (m_o.estimate_range_bias) {
                const double estimate = m_mapRangeBias + a.rangeBiasChange;
                m_rangeBias = std::clamp(
                    m_rangeBias + m_o.range_bias_rate * (estimate - m_rangeBias),
                    -m_o.max_range_bias, m_o.max_range_bias);
            }
        } else {
            m_stats.refused++;
        }
    }
    if (std::hypot(m_pose.x - m_keyframe.x, m_pose.y - m_keyframe.y) >=
            m_o.keyframe_distance ||
        std::abs(mrpt::math::wrapToPi(m_pose.phi - m_keyframe.phi)) >=
            m_o.keyframe_angle_deg * M_PI / 180)
        addToMap(raw, dirs, m_pose);
    return m_pose;
}
}  // namespace risknav::speed
