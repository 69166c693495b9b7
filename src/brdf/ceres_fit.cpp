// ceres_fit.cpp - the library's only C++: a thin extern "C" shim that solves a bounded nonlinear
// least-squares problem given by a C residual callback with Ceres Solver (claim D15's fits).
// Exceptions never cross into C; Ceres and glog stay silent.
#include <ceres/ceres.h>
#include <glog/logging.h>

#include <cmath>
#include <mutex>
#include <vector>

#include "sol_brdf.h"

namespace {

// Ceres logs through glog; only fatal messages may get through (a failed problem is reported as a
// status instead).
void silence_glog()
{
    static std::once_flag once;
    std::call_once(once, [] { FLAGS_minloglevel = google::GLOG_FATAL; });
}

// One residual block holding all residuals and one parameter block: the callback gives the
// row-major Jacobian Ceres expects for a single block.
class CallbackCost final : public ceres::CostFunction {
public:
    explicit CallbackCost(const sol_lsq_problem &p) : problem_(p)
    {
        set_num_residuals(p.n_residuals);
        mutable_parameter_block_sizes()->push_back(p.n_params);
    }
    bool Evaluate(double const *const *params, double *residuals, double **jacobians) const override
    {
        double *jac = jacobians ? jacobians[0] : nullptr;
        return problem_.fn(problem_.ctx, params[0], residuals, jac) == 0;
    }

private:
    const sol_lsq_problem &problem_;
};

sol_status validate(const sol_lsq_problem *p, const double *params)
{
    if (!p || !params || !p->fn)
        return SOL_ERR_NULL_ARG;
    if (p->n_params < 1 || p->n_residuals < 1)
        return SOL_ERR_INVALID_ARG;
    if (p->linear_solver != SOL_LSQ_DENSE_NORMAL_CHOLESKY && p->linear_solver != SOL_LSQ_DENSE_QR)
        return SOL_ERR_INVALID_ARG;
    for (int i = 0; i < p->n_params; ++i) {
        if (!std::isfinite(params[i]))
            return SOL_ERR_NONFINITE;
        if ((p->lower && params[i] < p->lower[i]) || (p->upper && params[i] > p->upper[i]))
            return SOL_ERR_INVALID_ARG;
    }
    return SOL_OK;
}

} // namespace

extern "C" sol_status sol_lsq_solve(const sol_lsq_problem *problem, double *params, sol_lsq_summary *summary)
{
    sol_status st = validate(problem, params);
    if (st != SOL_OK)
        return st;
    try {
        silence_glog();
        std::vector<double> x(params, params + problem->n_params);
        ceres::Problem::Options problem_options;
        ceres::Problem cp(problem_options);
        cp.AddResidualBlock(new CallbackCost(*problem), nullptr, x.data());
        for (int i = 0; i < problem->n_params; ++i) {
            if (problem->lower)
                cp.SetParameterLowerBound(x.data(), i, problem->lower[i]);
            if (problem->upper)
                cp.SetParameterUpperBound(x.data(), i, problem->upper[i]);
        }
        ceres::Solver::Options options;
        // The normal equations (J^T J, m n^2 / 2 flops) cost a quarter of a QR of J (2 m n^2) and give
        // the same fits here (d15's bench table); QR stays available for ill-conditioned problems.
        options.linear_solver_type =
            problem->linear_solver == SOL_LSQ_DENSE_QR ? ceres::DENSE_QR : ceres::DENSE_NORMAL_CHOLESKY;
        options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
        options.max_num_iterations = problem->max_iterations > 0 ? problem->max_iterations : 100;
        options.num_threads = 1;
        options.logging_type = ceres::SILENT;
        options.minimizer_progress_to_stdout = false;
        options.function_tolerance = 1e-10;
        options.parameter_tolerance = 1e-10;
        options.gradient_tolerance = 1e-12;
        ceres::Solver::Summary s;
        ceres::Solve(options, &cp, &s);
        if (!s.IsSolutionUsable() || !std::isfinite(s.final_cost))
            return SOL_ERR_SOLVER;
        for (double v : x)
            if (!std::isfinite(v))
                return SOL_ERR_SOLVER;
        std::copy(x.begin(), x.end(), params);
        if (summary) {
            summary->initial_cost = s.initial_cost;
            summary->final_cost = s.final_cost;
            summary->iterations = static_cast<int>(s.iterations.size());
            summary->converged = s.termination_type == ceres::CONVERGENCE;
            summary->solve_seconds = s.total_time_in_seconds;
        }
        return SOL_OK;
    } catch (...) {
        return SOL_ERR_SOLVER;
    }
}
