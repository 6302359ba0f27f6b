#include <risknav/risk/CPosePropagator.h>

#include <mrpt/math/wrap2pi.h>

#include <cmath>

namespace risknav::risk {
namespace {
// A symmetric square root S S^T = C of a PSD covariance (eigenvalues below
// zero, from rounding, taken as zero): singular covariances are allowed.
Eigen::Matrix3d sqrtPsd(const Eigen::Matrix3d& c) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(0.5 * (c + c.transpose()));
    return es.eigenvectors() * es.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal() *
           es.eigenvectors().transpose();
}
}  // namespace

CPosePropagator::CPosePropagator(const TOdometryModel& m, TErrorModel model,
                                 TPropagation propagation, const Eigen::Matrix3d& sigmaP0,
                                 double x0, double y0, double theta0, int samples,
                                 uint64_t seed)
    : m_m(m), m_model(model), m_linear(propagation == TPropagation::Linear) {
    m_plan = Eigen::Vector3d(x0, y0, theta0);
    m_p = sigmaP0;
    m_z = augmentedInitial(sigmaP0, m);
    if (m_linear)
        return;
    const bool systematic = model == TErrorModel::Systematic;
    const int n = systematic ? 6 : 3;
    TSigmaPoints sp;
    switch (propagation) {
        case TPropagation::Unscented:
            sp = unscentedPoints(n);
            break;
        case TPropagation::Cubature5:
            sp = cubature5Points(n);
            break;
        default:
            sp = sampledPoints(n, samples, seed);
            m_unbiased = samples > 1;
            m_sampled = true;
            m_rng.seed(seed ^ 0x9e3779b97f4a7c15ULL);  // not the points' stream
            m_noiseSqrt = sqrtPsd(m.sigmaN);
    }
    m_xi = std::move(sp.points);
    m_w = std::move(sp.weights);
    // Per-step errors: the wheel errors of per_step, the process noise.
    m_stepNoise = !m.sigmaN.isZero() || (!systematic && !m.sigmaM().isZero());
    if (m_sampled)
        m_stepNoise = false;  // drawn, not linearised
    const Eigen::Vector3d nominal(m.radiusL, m.radiusR, m.tread);
    const Eigen::Vector3d sm(m.sigmaRL, m.sigmaRR, m.sigmaT);
    m_wheel.resize(m_xi.size(), nominal);
    if (systematic)
        for (size_t j = 0; j < m_xi.size(); j++)
            m_wheel[j] += sm.cwiseProduct(m_xi[j].tail<3>());
    placePoses(sigmaP0);
}

void CPosePropagator::placePoses(const Eigen::Matrix3d& cov) {
    const Eigen::Matrix3d s = sqrtPsd(cov);
    m_pose.resize(m_xi.size());
    for (size_t j = 0; j < m_xi.size(); j++)
        m_pose[j] = m_plan + s * m_xi[j].head<3>();
    m_cond.assign(m_xi.size(), Eigen::Matrix3d::Zero());
}

void CPosePropagator::step(double thetaStart, double uL, double uR, double tau, double x,
                           double y, double theta) {
    m_plan[2] = thetaStart;
    if (m_linear) {
        if (m_model == TErrorModel::PerStep)
            m_p = propagatePerStep(m_p, m_plan[2], uL, uR, tau, m_m);
        else
            m_z = propagateSystematic(m_z, m_plan[2], uL, uR, tau, m_m);
    } else {
        const bool perStep = m_model == TErrorModel::PerStep;
        const bool drawWheels = m_sampled && perStep && !m_m.sigmaM().isZero();
        const bool drawNoise = m_sampled && !m_m.sigmaN.isZero();
        std::normal_distribution<double> n01;
        for (size_t j = 0; j < m_pose.size(); j++) {
            Eigen::Vector3d& p = m_pose[j];
            common::TWheelGeometry g{m_wheel[j][0], m_wheel[j][1], m_wheel[j][2]};
            if (drawWheels) {  // a fresh wheel error every step (eq. 15's model)
                g.radiusL += m_m.sigmaRL * n01(m_rng);
                g.radiusR += m_m.sigmaRR * n01(m_rng);
                g.tread += m_m.sigmaT * n01(m_rng);
            }
            double v, w;
            common::twistFromWheels(g, uL, uR, v, w);
            if (m_stepNoise) {
                // Eq. (15) along this point's trajectory: its heading in J_P
                // and J_V; with per_step its wheels are the nominal ones.
                if (perStep)
                    m_cond[j] = propagatePerStep(m_cond[j], p[2], uL, uR, tau, m_m);
                else {
                    const Eigen::Matrix3d jp = jacobianPose(p[2], v, tau);
                    m_cond[j] = jp * m_cond[j] * jp.transpose() + tau * tau * m_m.sigmaN;
                }
            }
            // Eq. (3): P += tau (v cos th, v sin th, omega) (+ tau n, drawn).
            p[0] += tau * v * std::cos(p[2]);
            p[1] += tau * v * std::sin(p[2]);
            p[2] += tau * w;
            if (drawNoise)
                p += tau * m_noiseSqrt *
                     Eigen::Vector3d(n01(m_rng), n01(m_rng), n01(m_rng));
        }
    }
    m_plan = Eigen::Vector3d(x, y, theta);
}

void CPosePropagator::reset(const Eigen::Matrix3d& cov) {
    if (m_linear) {
        m_p = cov;
        m_z.block<3, 3>(0, 0) = cov;
        m_z.block<3, 3>(0, 3).setZero();
        m_z.block<3, 3>(3, 0).setZero();
    } else
        placePoses(cov);
}

Eigen::Vector3d CPosePropagator::bias() const {
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    if (m_linear)
        return b;
    for (size_t j = 0; j < m_pose.size(); j++) {
        Eigen::Vector3d d = m_pose[j] - m_plan;
        d[2] = mrpt::math::wrapToPi(d[2]);
        b += m_w[j] * d;
    }
    return b;
}

Eigen::Matrix3d CPosePropagator::covariance() const {
    if (m_linear)
        return m_model == TErrorModel::PerStep ? m_p
                                               : Eigen::Matrix3d(m_z.block<3, 3>(0, 0));
    const Eigen::Vector3d b = bias();
    Eigen::Matrix3d spread = Eigen::Matrix3d::Zero(), cond = Eigen::Matrix3d::Zero();
    for (size_t j = 0; j < m_pose.size(); j++) {
        Eigen::Vector3d d = m_pose[j] - m_plan;
        d[2] = mrpt::math::wrapToPi(d[2]);
        d -= b;
        spread += m_w[j] * d * d.transpose();
        if (m_stepNoise)
            cond += m_w[j] * m_cond[j];
    }
    if (m_unbiased)
        spread *= double(m_pose.size()) / double(m_pose.size() - 1);
    return spread + cond;
}

Eigen::Matrix3d CPosePropagator::secondMoment() const {
    const Eigen::Vector3d b = bias();
    return covariance() + b * b.transpose();
}

}  // namespace risknav::risk
