// fit_ceres.cc — the C++ bridge from fit_ceres.h to Ceres (see the header).
#include "models/fit_ceres.h"

#include <ceres/ceres.h>
#include <Eigen/SVD>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

extern "C" {
#include "core/dm_error.h"
}

namespace {

// One residual of one point; Ceres owns it through the Problem.
class PointCost final : public ceres::CostFunction {
public:
    PointCost(const fit_ceres_problem *pb, size_t i) : pb_(pb), i_(i)
    {
        set_num_residuals(1);
        mutable_parameter_block_sizes()->push_back(static_cast<int>(pb->n_params));
    }
    bool Evaluate(double const *const *parameters, double *residuals,
                  double **jacobians) const override
    {
        double *jac = jacobians ? jacobians[0] : nullptr;
        return pb_->residual(pb_->user, i_, parameters[0], residuals, jac) == 0;
    }

private:
    const fit_ceres_problem *pb_;
    size_t i_;
};

std::unique_ptr<ceres::LossFunction> make_loss(const fit_ceres_problem *pb)
{
    switch (pb->loss) {
    case FIT_CERES_LOSS_HUBER: return std::make_unique<ceres::HuberLoss>(pb->loss_scale);
    case FIT_CERES_LOSS_CAUCHY: return std::make_unique<ceres::CauchyLoss>(pb->loss_scale);
    default: return nullptr;
    }
}

void set_bounds_and_fixed(const fit_ceres_problem *pb, ceres::Problem &problem, double *theta)
{
    int n = static_cast<int>(pb->n_params);
    std::vector<int> fixed;
    for (int j = 0; j < n; j++) {
        if (pb->lo && std::isfinite(pb->lo[j]))
            problem.SetParameterLowerBound(theta, j, pb->lo[j]);
        if (pb->hi && std::isfinite(pb->hi[j]))
            problem.SetParameterUpperBound(theta, j, pb->hi[j]);
        if (pb->fixed && pb->fixed[j])
            fixed.push_back(j);
    }
    if (!fixed.empty())
        problem.SetManifold(theta, new ceres::SubsetManifold(n, fixed));
}

// The dense Jacobian the solver sees at theta; false when it cannot be evaluated.
// Ceres reports through glog; uninitialised, glog prints "Logging before
// InitGoogleLogging()" and Ceres' warnings on stderr, which are not dmbench's
// messages (the fit's own warnings say what matters).  Initialised once to
// stderr only (no log files) and fatal errors only.
void quiet_glog()
{
    static bool done = false;
    if (done)
        return;
    done = true;
    FLAGS_logtostderr = true;
    FLAGS_minloglevel = google::GLOG_FATAL;
    if (!google::IsGoogleLoggingInitialized())
        google::InitGoogleLogging("dmbench");
}

bool dense_jacobian(ceres::Problem &problem, size_t n_params, Eigen::MatrixXd *j)
{
    ceres::CRSMatrix crs;
    if (!problem.Evaluate(ceres::Problem::EvaluateOptions(), nullptr, nullptr, nullptr, &crs))
        return false;
    *j = Eigen::MatrixXd::Zero(crs.num_rows, static_cast<Eigen::Index>(n_params));
    for (int r = 0; r < crs.num_rows; r++)
        for (int k = crs.rows[r]; k < crs.rows[r + 1]; k++)
            (*j)(r, crs.cols[k]) = crs.values[k];
    return true;
}

// Condition number sigma_max / sigma_min of the Jacobian, with Ceres' own
// rank criterion (sigma_min/sigma_max)^2 < min_rcond giving INFINITY (checked
// before Covariance::Compute, which would otherwise log an error on stderr).
// weak_dir (n_params, may be NULL) receives the right singular vector of
// sigma_min.  Returns 0 when the Jacobian cannot be evaluated.
double condition(ceres::Problem &problem, size_t n_params, double min_rcond, double *weak_dir)
{
    Eigen::MatrixXd j;
    if (!dense_jacobian(problem, n_params, &j))
        return 0.0;
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(j, Eigen::ComputeThinV);
    const Eigen::VectorXd &sv = svd.singularValues();
    Eigen::Index last = sv.size() - 1;
    for (size_t k = 0; weak_dir && k < n_params; k++)
        weak_dir[k] = svd.matrixV()(static_cast<Eigen::Index>(k), last);
    double lo = sv(last), hi = sv(0);
    if (!(hi > 0.0) || sv.size() < static_cast<Eigen::Index>(n_params)
        || (lo / hi) * (lo / hi) < min_rcond)
        return INFINITY;
    return hi / lo;
}

// Covariance of theta and the condition number (summary); cov_ok = 0 when
// the Jacobian is rank deficient.
void covariance(ceres::Problem &problem, const fit_ceres_problem *pb, double *theta,
                fit_ceres_summary *summary)
{
    ceres::Covariance::Options opt;
    opt.algorithm_type = ceres::DENSE_SVD;
    opt.null_space_rank = 0;
    summary->condition = condition(problem, pb->n_params, opt.min_reciprocal_condition_number,
                                   pb->weak_dir);
    if (!(summary->condition > 0.0) || std::isinf(summary->condition))
        return;
    ceres::Covariance c(opt);
    std::vector<std::pair<const double *, const double *>> blocks{ { theta, theta } };
    summary->cov_ok = c.Compute(blocks, &problem) && c.GetCovarianceBlock(theta, theta, pb->cov);
}

}  // namespace

extern "C" int fit_ceres_solve(const fit_ceres_problem *pb, double *theta,
                               fit_ceres_summary *summary)
{
    quiet_glog();
    std::memset(summary, 0, sizeof *summary);
    size_t n_fixed = 0;
    for (size_t j = 0; pb->fixed && j < pb->n_params; j++)
        n_fixed += pb->fixed[j] != 0;
    if (pb->n_params == 0 || n_fixed == pb->n_params || pb->n_residuals == 0)
        return DM_ERR_ARG;
    std::unique_ptr<ceres::LossFunction> loss = make_loss(pb);
    ceres::Problem::Options popt;
    popt.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem problem(popt);
    for (size_t i = 0; i < pb->n_residuals; i++)
        problem.AddResidualBlock(new PointCost(pb, i), loss.get(), theta);
    set_bounds_and_fixed(pb, problem, theta);

    ceres::Solver::Options opt;
    opt.linear_solver_type = ceres::DENSE_QR;
    opt.logging_type = ceres::SILENT;
    opt.max_num_iterations = pb->max_iterations > 0 ? pb->max_iterations : 200;
    opt.initial_trust_region_radius = 1e12;   // ~Gauss-Newton: exact in one step when linear
    opt.function_tolerance = 1e-15;
    opt.gradient_tolerance = 1e-20;
    opt.parameter_tolerance = 1e-14;
    ceres::Solver::Summary sum;
    ceres::Solve(opt, &problem, &sum);

    summary->iterations = sum.iterations.empty() ? 0 : static_cast<int>(sum.iterations.size()) - 1;
    summary->final_cost = sum.final_cost;
    summary->converged = sum.termination_type == ceres::CONVERGENCE;
    summary->usable = (summary->converged || sum.termination_type == ceres::NO_CONVERGENCE)
                      && std::isfinite(sum.final_cost);
    std::snprintf(summary->termination, sizeof summary->termination, "%s",
                  ceres::TerminationTypeToString(sum.termination_type));
    std::snprintf(summary->message, sizeof summary->message, "%s", sum.message.c_str());
    if (pb->cov && summary->usable && n_fixed == 0)
        covariance(problem, pb, theta, summary);
    return 0;
}
