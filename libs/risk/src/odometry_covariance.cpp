#include <risknav/risk/odometry_covariance.h>

#include <cmath>
#include <random>

namespace risknav::risk {
Eigen::Matrix3d TOdometryModel::sigmaM() const {
    Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
    s(0, 0) = sigmaRL * sigmaRL;
    s(1, 1) = sigmaRR * sigmaRR;
    s(2, 2) = sigmaT * sigmaT;
    return s;
}

Eigen::Matrix3d jacobianPose(double theta, double v, double tau) {
    Eigen::Matrix3d j = Eigen::Matrix3d::Identity();
    j(0, 2) = -tau * v * std::sin(theta);
    j(1, 2) = tau * v * std::cos(theta);
    return j;
}

Eigen::Matrix<double, 3, 2> jacobianVelocity(double theta, double tau) {
    Eigen::Matrix<double, 3, 2> k = Eigen::Matrix<double, 3, 2>::Zero();
    k(0, 0) = tau * std::cos(theta);
    k(1, 0) = tau * std::sin(theta);
    k(2, 1) = tau;
    return k;
}

Eigen::Matrix<double, 2, 3> jacobianWheelParams(const TOdometryModel& m, double uL,
                                                double uR) {
    Eigen::Matrix<double, 2, 3> l;
    l << uL / 2, uR / 2, 0,  //
        -uL / m.tread, uR / m.tread,
        -(m.radiusR * uR - m.radiusL * uL) / (m.tread * m.tread);
    return l;
}

Eigen::Matrix3d propagatePerStep(const Eigen::Matrix3d& sigmaP, double theta, double uL,
                                 double uR, double tau, const TOdometryModel& m) {
    double v, w;
    twistFromWheels(m, uL, uR, v, w);
    const Eigen::Matrix3d jp = jacobianPose(theta, v, tau);
    const Eigen::Matrix<double, 3, 2> jv = jacobianVelocity(theta, tau);
    const Eigen::Matrix<double, 2, 3> l = jacobianWheelParams(m, uL, uR);
    const Eigen::Matrix2d sigmaV = l * m.sigmaM() * l.transpose();
    return jp * sigmaP * jp.transpose() + jv * sigmaV * jv.transpose() +
           tau * tau * m.sigmaN;
}

Eigen::Matrix<double, 6, 6> propagateSystematic(const Eigen::Matrix<double, 6, 6>& sigmaZ,
                                                double theta, double uL, double uR,
                                                double tau, const TOdometryModel& m) {
    double v, w;
    twistFromWheels(m, uL, uR, v, w);
    Eigen::Matrix<double, 6, 6> f = Eigen::Matrix<double, 6, 6>::Identity();
    f.block<3, 3>(0, 0) = jacobianPose(theta, v, tau);
    f.block<3, 3>(0, 3) = jacobianVelocity(theta, tau) * jacobianWheelParams(m, uL, uR);
    Eigen::Matrix<double, 6, 6> out = f * sigmaZ * f.transpose();
    out.block<3, 3>(0, 0) += tau * tau * m.sigmaN;
    return out;
}

Eigen::Matrix<double, 6, 6> augmentedInitial(const Eigen::Matrix3d& sigmaP0,
                                             const TOdometryModel& m) {
    Eigen::Matrix<double, 6, 6> z = Eigen::Matrix<double, 6, 6>::Zero();
    z.block<3, 3>(0, 0) = sigmaP0;
    z.block<3, 3>(3, 3) = m.sigmaM();
    return z;
}

TSigmaPoints unscentedPoints(int n) {
    TSigmaPoints s;
    for (int i = 0; i < n; i++)
        for (double sign : {-1.0, 1.0}) {
            Eigen::VectorXd p = Eigen::VectorXd::Zero(n);
            p[i] = sign * std::sqrt(double(n));
            s.points.push_back(p);
            s.weights.push_back(0.5 / n);
        }
    return s;
}

TSigmaPoints cubature5Points(int n) {
    TSigmaPoints s;
    const double n2 = n + 2.0, r = std::sqrt(n2);
    s.points.push_back(Eigen::VectorXd::Zero(n));
    s.weights.push_back(2.0 / n2);
    for (int i = 0; i < n; i++)
        for (double sign : {-1.0, 1.0}) {
            Eigen::VectorXd p = Eigen::VectorXd::Zero(n);
            p[i] = sign * r;
            s.points.push_back(p);
            s.weights.push_back((4.0 - n) / (2.0 * n2 * n2));
        }
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++)
            for (double si : {-1.0, 1.0})
                for (double sj : {-1.0, 1.0}) {
                    Eigen::VectorXd p = Eigen::VectorXd::Zero(n);
                    p[i] = si * r / std::sqrt(2.0);
                    p[j] = sj * r / std::sqrt(2.0);
                    s.points.push_back(p);
                    s.weights.push_back(1.0 / (n2 * n2));
                }
    return s;
}

TSigmaPoints sampledPoints(int n, int count, uint64_t seed) {
    TSigmaPoints s;
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> n01;
    for (int k = 0; k < count; k++) {
        Eigen::VectorXd p(n);
        for (int i = 0; i < n; i++)
            p[i] = n01(rng);
        s.points.push_back(p);
        s.weights.push_back(1.0 / count);
    }
    return s;
}

}  // namespace risknav::risk
