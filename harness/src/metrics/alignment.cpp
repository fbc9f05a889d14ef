#include "metrics/alignment.hpp"

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include <cmath>
#include <stdexcept>

namespace vobench::metrics {

AlignmentMethod parse_alignment(const std::string& name) {
    if (name == "se3") return AlignmentMethod::Se3;
    if (name == "sim3") return AlignmentMethod::Sim3;
    if (name == "posyaw") return AlignmentMethod::PosYaw;
    if (name == "none") return AlignmentMethod::None;
    throw std::invalid_argument("unknown alignment '" + name + "' (se3, sim3, posyaw or none)");
}

const char* alignment_name(AlignmentMethod method) {
    switch (method) {
        case AlignmentMethod::Se3: return "se3";
        case AlignmentMethod::Sim3: return "sim3";
        case AlignmentMethod::PosYaw: return "posyaw";
        case AlignmentMethod::None: return "none";
    }
    return "?";
}

namespace {

// Umeyama (1991): R = U S Vᵀ from the SVD of the cross-covariance Σ_dm = U D Vᵀ, S = diag(1, 1, −1)
// when det(U)·det(V) < 0 (a reflection), c = tr(D S) / σ_m² (eq. 42), t = μ_d − c R μ_m.
Alignment umeyama(const Eigen::Matrix3Xd& m, const Eigen::Matrix3Xd& d, bool with_scale) {
    const double n = static_cast<double>(m.cols());
    const Eigen::Vector3d mu_m = m.rowwise().mean();
    const Eigen::Vector3d mu_d = d.rowwise().mean();
    const Eigen::Matrix3Xd mc = m.colwise() - mu_m;
    const Eigen::Matrix3Xd dc = d.colwise() - mu_d;
    const Eigen::Matrix3d sigma = dc * mc.transpose() / n;
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(sigma, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Vector3d s = Eigen::Vector3d::Ones();
    if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0) s(2) = -1;
    Alignment a;
    a.R = svd.matrixU() * s.asDiagonal() * svd.matrixV().transpose();
    if (with_scale) {
        const double var_m = mc.squaredNorm() / n;
        if (!(var_m > 0)) throw std::invalid_argument("sim3 alignment: the estimate's positions do not spread");
        a.scale = svd.singularValues().dot(s) / var_m;
    }
    a.t = mu_d - a.scale * a.R * mu_m;
    return a;
}

// Rotation about z minimising the squared residuals of centred points: θ = atan2(Σ mx dy − my dx,
// Σ mx dx + my dy).
Alignment pos_yaw(const Eigen::Matrix3Xd& m, const Eigen::Matrix3Xd& d) {
    const Eigen::Vector3d mu_m = m.rowwise().mean();
    const Eigen::Vector3d mu_d = d.rowwise().mean();
    double sin_sum = 0, cos_sum = 0;
    for (Eigen::Index i = 0; i < m.cols(); ++i) {
        const Eigen::Vector3d a = m.col(i) - mu_m, b = d.col(i) - mu_d;
        sin_sum += a.x() * b.y() - a.y() * b.x();
        cos_sum += a.x() * b.x() + a.y() * b.y();
    }
    Alignment out;
    out.R = Eigen::AngleAxisd(std::atan2(sin_sum, cos_sum), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    out.t = mu_d - out.R * mu_m;
    return out;
}

}  // namespace

Alignment align(const Eigen::Matrix3Xd& model, const Eigen::Matrix3Xd& data, AlignmentMethod method, std::size_t first_n) {
    if (model.cols() != data.cols()) throw std::invalid_argument("alignment needs as many model as data points");
    const Eigen::Index n = first_n > 0 ? std::min<Eigen::Index>(static_cast<Eigen::Index>(first_n), model.cols()) : model.cols();
    const Eigen::Matrix3Xd m = model.leftCols(n), d = data.leftCols(n);
    const Eigen::Index needed = method == AlignmentMethod::None ? 0 : method == AlignmentMethod::PosYaw ? 2 : 3;
    if (n < needed)
        throw std::invalid_argument(std::string(alignment_name(method)) + " alignment needs at least " + std::to_string(needed) +
                                    " matched poses, got " + std::to_string(n));
    switch (method) {
        case AlignmentMethod::Se3: return umeyama(m, d, false);
        case AlignmentMethod::Sim3: return umeyama(m, d, true);
        case AlignmentMethod::PosYaw: return pos_yaw(m, d);
        case AlignmentMethod::None: return Alignment{};
    }
    return Alignment{};
}

}  // namespace vobench::metrics
