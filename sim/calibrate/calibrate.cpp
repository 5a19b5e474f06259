// Bounded Levenberg-Marquardt fit of per-event costs to target speedups, and
// the Gauss-Newton error analysis at the optimum (see calibrate.h).
//
// With fitted values theta_k, each run's cycles are affine in theta:
//     C(theta) = base + sum_k theta_k * a_k
// where base prices the events not fitted and a_k sums the counts of
// parameter k's events (times their start cost for Tie::Scale). The residual
// r_i = sqrt(w_i) * (log C_ref - log C_obb - log target) then has the exact
// derivative sqrt(w_i) * (a_ref_k / C_ref - a_obb_k / C_obb).
#include "sim/calibrate/calibrate.h"
#include "sim/calibrate/calibrate_report.h"
#include "sim/calibrate/linear_algebra.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace rtc {
namespace {


struct Side {
    double base = 0.0;
    Vec a;
};
struct Row {
    Side ref, obb;
    double log_target = 0.0;
    double sqrt_w = 1.0;
    const CalibrationRun* warp_run = nullptr;  // set: sides depend on theta (re-linearized)
};

// What every re-linearization needs.
struct FitContext {
    const CostModel& start;
    const std::vector<FitParameter>& params;
    const std::vector<int>& owner;
};

[[nodiscard]] std::string fmt(double x, const char* spec = "%.6g") {
    char buf[64];
    std::snprintf(buf, sizeof buf, spec, x);
    return buf;
}

// Effective counts indexed like EventTotals.
struct EffectiveView {
    const EffectiveCounts& c;
    double operator[](Event e) const { return c[static_cast<std::size_t>(e)]; }
};

[[nodiscard]] double multiplier(const FitParameter& p, Event e, const CostModel& start) {
    return p.tie == Tie::Scale ? start[e] : 1.0;
}

template <class Counts>
[[nodiscard]] Side make_side(const Counts& n, const CostModel& start,
                             const std::vector<FitParameter>& params,
                             const std::vector<int>& owner) {
    Side s;
    s.a.assign(params.size(), 0.0);
    for (std::size_t i = 0; i < kEventCount; ++i) {
        const double count = static_cast<double>(n[static_cast<Event>(i)]);
        if (owner[i] < 0) {
            s.base += count * start.cycles[i];
        } else {
            const FitParameter& p = params[static_cast<std::size_t>(owner[i])];
            s.a[static_cast<std::size_t>(owner[i])] += count * multiplier(p, static_cast<Event>(i), start);
        }
    }
    return s;
}

[[nodiscard]] double cycles(const Side& s, const Vec& theta) {
    double c = s.base;
    for (std::size_t k = 0; k < theta.size(); ++k) c += theta[k] * s.a[k];
    return c;
}

[[nodiscard]] CostModel model_at(const FitContext& fit, const Vec& theta) {
    CostModel m = fit.start;
    for (std::size_t k = 0; k < fit.params.size(); ++k)
        for (Event e : fit.params[k].events) m[e] = theta[k] * multiplier(fit.params[k], e, fit.start);
    m.settle();
    return m;
}

// Warp-model cycles are piecewise linear in the costs: at theta, the lanes and
// calls that take each max fix effective counts whose linear price is exact
// there (sim/hardware/warp_pricing.h). Rows of warp runs are re-made at theta.
void relinearize(std::vector<Row>& rows, const Vec& theta, const FitContext& fit) {
    CostModel m;
    bool made = false;
    for (Row& row : rows) {
        if (!row.warp_run) continue;
        if (!made) m = model_at(fit, theta), made = true;
        EffectiveCounts er{}, eo{};
        (void)row.warp_run->ref_warps->price(m, row.warp_run->ref_roof, er);
        (void)row.warp_run->obb_warps->price(m, row.warp_run->obb_roof, eo);
        row.ref = make_side(EffectiveView{er}, fit.start, fit.params, fit.owner);
        row.obb = make_side(EffectiveView{eo}, fit.start, fit.params, fit.owner);
    }
}

// Residuals; false when some run's cycles are not positive (a forbidden point).
[[nodiscard]] bool residuals(std::vector<Row>& rows, const Vec& theta, Vec& r, const FitContext& fit) {
    relinearize(rows, theta, fit);
    r.assign(rows.size(), 0.0);
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const double cr = cycles(rows[i].ref, theta), co = cycles(rows[i].obb, theta);
        if (!(cr > 0.0) || !(co > 0.0)) return false;
        r[i] = rows[i].sqrt_w * (std::log(cr) - std::log(co) - rows[i].log_target);
    }
    return true;
}

[[nodiscard]] Mat jacobian(std::vector<Row>& rows, const Vec& theta, const FitContext& fit) {
    relinearize(rows, theta, fit);
    Mat J(rows.size(), Vec(theta.size(), 0.0));
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const double cr = cycles(rows[i].ref, theta), co = cycles(rows[i].obb, theta);
        for (std::size_t k = 0; k < theta.size(); ++k)
            J[i][k] = rows[i].sqrt_w * (rows[i].ref.a[k] / cr - rows[i].obb.a[k] / co);
    }
    return J;
}

[[nodiscard]] double half_ssr(const Vec& r) {
    double s = 0.0;
    for (double x : r) s += x * x;
    return 0.5 * s;
}

void validate(const std::vector<CalibrationRun>& runs, const std::vector<FitParameter>& params,
              std::vector<int>& owner) {
    if (runs.empty()) throw std::invalid_argument("calibrate: no runs");
    for (const CalibrationRun& run : runs) {
        if (!(run.target_speedup > 0.0) || !std::isfinite(run.target_speedup))
            throw std::invalid_argument("calibrate: run '" + run.label +
                                        "': target speedup must be positive, got " +
                                        fmt(run.target_speedup));
        if (!(run.weight >= 0.0) || !std::isfinite(run.weight))
            throw std::invalid_argument("calibrate: run '" + run.label +
                                        "': weight must be >= 0, got " + fmt(run.weight));
    }
    owner.assign(kEventCount, -1);
    for (std::size_t k = 0; k < params.size(); ++k) {
        const FitParameter& p = params[k];
        if (p.events.empty()) throw std::invalid_argument("calibrate: parameter without events");
        if (!(p.lo >= 0.0) || !(p.hi >= p.lo) || !std::isfinite(p.hi))
            throw std::invalid_argument("calibrate: " + parameter_label(p) + ": bounds must satisfy 0 <= min <= max < inf, got [" +
                                        fmt(p.lo) + ", " + fmt(p.hi) + "]");
        for (Event e : p.events) {
            int& o = owner[static_cast<std::size_t>(e)];
            if (o >= 0)
                throw std::invalid_argument("calibrate: event " + std::string(event_name(e)) +
                                            " is in more than one parameter");
            o = static_cast<int>(k);
        }
    }
}

// Scale of parameter k for relative tests: its value, or a bit of its range.
[[nodiscard]] double scale_of(double theta, const FitParameter& p) {
    return std::max({std::abs(theta), 1e-3 * (p.hi - p.lo), 1e-12});
}

struct LmOutcome {
    Vec theta;
    int iterations = 0;
    bool converged = false;
};

// Projected LM: parameters held at a bound by the gradient are frozen for the
// step; the step of the others is clipped into the box.
[[nodiscard]] LmOutcome levenberg_marquardt(std::vector<Row>& rows, Vec theta,
                                            const std::vector<FitParameter>& params,
                                            int max_iterations, const FitContext& fit) {
    const std::size_t np = theta.size();
    LmOutcome out;
    Vec r;
    (void)residuals(rows, theta, r, fit);  // validated positive by the caller
    double cost = half_ssr(r);
    double lambda = 1e-3;
    for (; out.iterations < max_iterations && !out.converged; ++out.iterations) {
        if (cost <= 1e-30) { out.converged = true; break; }
        const Mat J = jacobian(rows, theta, fit);
        Vec g(np, 0.0);
        Mat A(np, Vec(np, 0.0));
        for (std::size_t i = 0; i < rows.size(); ++i)
            for (std::size_t k = 0; k < np; ++k) {
                g[k] += J[i][k] * r[i];
                for (std::size_t l = 0; l < np; ++l) A[k][l] += J[i][k] * J[i][l];
            }
        std::vector<std::size_t> free;
        double max_diag = 0.0;
        for (std::size_t k = 0; k < np; ++k) {
            const bool held = (theta[k] <= params[k].lo && g[k] > 0.0) ||
                              (theta[k] >= params[k].hi && g[k] < 0.0) || params[k].lo == params[k].hi;
            if (!held) free.push_back(k);
            max_diag = std::max(max_diag, A[k][k]);
        }
        if (free.empty() || max_diag == 0.0) { out.converged = true; break; }
        bool accepted = false;
        while (!accepted) {
            Mat M(free.size(), Vec(free.size(), 0.0));
            Vec b(free.size(), 0.0), d;
            for (std::size_t a = 0; a < free.size(); ++a) {
                for (std::size_t c = 0; c < free.size(); ++c) M[a][c] = A[free[a]][free[c]];
                M[a][a] += lambda * std::max(A[free[a]][free[a]], 1e-12 * max_diag);
                b[a] = -g[free[a]];
            }
            Vec trial = theta;
            double rel_step = std::numeric_limits<double>::infinity();  // if the solve fails
            if (solve_spd(M, b, d)) {
                rel_step = 0.0;
                for (std::size_t a = 0; a < free.size(); ++a) {
                    const std::size_t k = free[a];
                    trial[k] = std::clamp(theta[k] + d[a], params[k].lo, params[k].hi);
                    rel_step = std::max(rel_step, std::abs(trial[k] - theta[k]) / scale_of(theta[k], params[k]));
                }
                Vec rt;
                if (residuals(rows, trial, rt, fit)) {
                    const double ct = half_ssr(rt);
                    if (ct < cost) {
                        const double decrease = cost - ct;
                        theta = trial, r = rt;
                        accepted = true;
                        lambda = std::max(lambda * 0.1, 1e-12);
                        if (ct <= 1e-30 || decrease <= 1e-15 * cost || rel_step <= 1e-13)
                            out.converged = true;
                        cost = ct;
                        continue;
                    }
                }
            }
            lambda *= 10.0;
            if (lambda > 1e14 || rel_step <= 1e-15) {  // no descent left: stationary
                out.converged = true;
                break;
            }
        }
    }
    out.theta = theta;
    return out;
}

}  // namespace

double predicted_speedup(const CalibrationRun& run, const CostModel& model) {
    if (model.execution.warp() && run.ref_warps && run.obb_warps)
        return run.ref_warps->price(model).cycles(run.ref_roof) / run.obb_warps->price(model).cycles(run.obb_roof);
    return price(run.ref, model).total_cycles / price(run.obb, model).total_cycles;
}

CalibrationResult calibrate(const std::vector<CalibrationRun>& runs, const CostModel& start,
                            const std::vector<FitParameter>& params,
                            const CalibrationOptions& options) {
    std::vector<int> owner;
    validate(runs, params, owner);
    const std::size_t np = params.size();

    Vec theta0(np, 0.0);
    for (std::size_t k = 0; k < np; ++k) {
        double v = 1.0;
        if (params[k].tie == Tie::Value) {
            v = 0.0;
            for (Event e : params[k].events) v += start[e];
            v /= static_cast<double>(params[k].events.size());
        }
        theta0[k] = std::clamp(v, params[k].lo, params[k].hi);
    }

    const FitContext fit{start, params, owner};
    const bool warp = start.execution.warp();
    std::vector<Row> rows;  // runs with weight > 0 only
    for (const CalibrationRun& run : runs) {
        if (warp && !(run.ref_warps && run.obb_warps))
            throw std::invalid_argument("calibrate: run '" + run.label + "': the start preset " + start.name +
                                        " is a warp model but the run kept no waves (list a warp preset in the run's costs)");
        Row row{make_side(run.ref, start, params, owner), make_side(run.obb, start, params, owner),
                std::log(run.target_speedup), std::sqrt(run.weight), warp ? &run : nullptr};
        std::vector<Row> one{row};
        relinearize(one, theta0, fit);
        row = one.front();
        if (!(cycles(row.ref, theta0) > 0.0) || !(cycles(row.obb, theta0) > 0.0))
            throw std::invalid_argument("calibrate: run '" + run.label +
                                        "': zero cycles at the start point (no counts, or all costs zero)");
        if (run.weight > 0.0) rows.push_back(std::move(row));
    }

    CalibrationResult res;
    res.observations = static_cast<int>(rows.size());
    const LmOutcome lm = rows.empty() ? LmOutcome{theta0, 0, true}
                                      : levenberg_marquardt(rows, theta0, params, options.max_iterations, fit);
    const Vec& theta = lm.theta;
    res.iterations = lm.iterations;
    res.converged = lm.converged;

    // The fitted model, with provenance on every fitted event.
    res.model = start;
    res.model.uncertainty.reset();  // the start's no longer applies; set below
    res.model.name = options.name.empty() ? start.name + "-calibrated" : options.name;
    if (!options.description.empty()) res.model.description = options.description;
    for (std::size_t k = 0; k < np; ++k)
        for (Event e : params[k].events) {
            const double old = start[e];
            res.model[e] = theta[k] * multiplier(params[k], e, start);
            res.model.source[static_cast<std::size_t>(e)] =
                "fitted by rtcsim calibrate to " + options.target_name + ", was " + fmt(old);
        }
    res.model.settle();  // costs made of fitted ones (sum_of) follow them

    // Per-run fit and RMS log errors.
    double sum_w = 0.0, ssr0 = 0.0, ssr = 0.0;
    for (const CalibrationRun& run : runs) {
        RunFit f{run.label, run.target_speedup, predicted_speedup(run, start),
                 predicted_speedup(run, res.model), 0.0};
        f.rel_error = f.fitted / f.target - 1.0;
        sum_w += run.weight;
        ssr0 += run.weight * std::pow(std::log(f.start / f.target), 2);
        ssr += run.weight * std::pow(std::log(f.fitted / f.target), 2);
        res.runs.push_back(std::move(f));
    }
    res.rms_log_error_start = sum_w > 0 ? std::sqrt(ssr0 / sum_w) : 0.0;
    res.rms_log_error = sum_w > 0 ? std::sqrt(ssr / sum_w) : 0.0;

    // Error analysis on the scaled Jacobian J S, S = diag(scale of each parameter).
    const Mat J = rows.empty() ? Mat{} : jacobian(rows, theta, fit);
    for (std::size_t k = 0; k < np; ++k) {
        ParameterFit pf;
        pf.events = params[k].events, pf.tie = params[k].tie;
        pf.lo = params[k].lo, pf.hi = params[k].hi;
        pf.start = theta0[k], pf.fitted = theta[k];
        double ss = 0.0;
        for (const Vec& row : J) ss += std::pow(theta[k] * row[k], 2);
        pf.sensitivity = sum_w > 0 ? std::sqrt(ss / sum_w) : 0.0;
        const double tol = 1e-9 * std::max(params[k].hi - params[k].lo, 1e-12);
        pf.at_lower = theta[k] <= params[k].lo + tol;
        pf.at_upper = !pf.at_lower && theta[k] >= params[k].hi - tol;
        pf.std_error = std::numeric_limits<double>::quiet_NaN();
        res.parameters.push_back(std::move(pf));
    }
    std::vector<std::size_t> cand;  // not at a bound, with some influence
    Vec s(np, 1.0);
    for (std::size_t k = 0; k < np; ++k) {
        ParameterFit& pf = res.parameters[k];
        s[k] = scale_of(theta[k], params[k]);
        double col = 0.0;
        for (const Vec& row : J) col += std::pow(s[k] * row[k], 2);
        if (col <= 1e-24 * std::max(sum_w, 1e-300)) {
            pf.unidentifiable = true;
            pf.std_error = std::numeric_limits<double>::infinity();
        } else if (!pf.at_lower && !pf.at_upper) {
            cand.push_back(k);
        }
    }
    Mat B(cand.size(), Vec(cand.size(), 0.0));
    for (const Vec& row : J)
        for (std::size_t a = 0; a < cand.size(); ++a)
            for (std::size_t c = 0; c < cand.size(); ++c)
                B[a][c] += s[cand[a]] * row[cand[a]] * s[cand[c]] * row[cand[c]];
    Vec w;
    Mat V;
    eigen_symmetric(B, w, V);
    const double wmax = w.empty() ? 0.0 : *std::max_element(w.begin(), w.end());
    Mat pinv(cand.size(), Vec(cand.size(), 0.0));  // the pseudo-inverse of B
    for (std::size_t j = 0; j < w.size(); ++j) {
        const bool null_dir = w[j] <= 1e-12 * wmax;
        for (std::size_t a = 0; a < cand.size(); ++a) {
            if (null_dir && std::abs(V[a][j]) > 0.2) res.parameters[cand[a]].unidentifiable = true;
            for (std::size_t c = 0; c < cand.size() && !null_dir; ++c) pinv[a][c] += V[a][j] * V[c][j] / w[j];
        }
    }
    for (std::size_t k : cand) res.free_parameters += res.parameters[k].unidentifiable ? 0 : 1;
    res.degrees_of_freedom = res.observations - res.free_parameters;
    Vec rfin;
    const double sigma2 = res.degrees_of_freedom > 0 && residuals(rows, theta, rfin, fit)
                              ? 2.0 * half_ssr(rfin) / res.degrees_of_freedom
                              : std::numeric_limits<double>::quiet_NaN();
    std::vector<std::size_t> fr;  // indices into cand of the free parameters
    for (std::size_t a = 0; a < cand.size(); ++a) {
        ParameterFit& pf = res.parameters[cand[a]];
        pf.std_error = pf.unidentifiable ? std::numeric_limits<double>::infinity()
                                         : s[cand[a]] * std::sqrt(sigma2 * pinv[a][a]);
        pf.free = !pf.unidentifiable && std::isfinite(pf.std_error);
        if (pf.free) fr.push_back(a);
    }
    // Cov(theta) = S sigma^2 B^+ S; over theta_a theta_c it is the covariance
    // of log theta to first order (free parameters are positive: not at lo >= 0).
    for (std::size_t a : fr) {
        res.log_covariance.emplace_back();
        for (std::size_t c : fr)
            res.log_covariance.back().push_back(sigma2 * pinv[a][c] * s[cand[a]] * s[cand[c]] /
                                                (theta[cand[a]] * theta[cand[c]]));
    }
    res.model.uncertainty = calibration_uncertainty(res);
    for (ParameterFit& pf : res.parameters) {
        std::string n = pf.tie == Tie::Scale ? "scale factor on the start costs" : "";
        const auto add = [&n](const std::string& x) { n += (n.empty() ? "" : "; ") + x; };
        if (pf.unidentifiable) add("UNIDENTIFIABLE: the targets do not determine it");
        if (pf.at_lower) add("at lower bound");
        if (pf.at_upper) add("at upper bound");
        if (!pf.unidentifiable && !pf.at_lower && !pf.at_upper) {
            if (std::isnan(pf.std_error)) add("no error estimate (degrees of freedom <= 0)");
            else if (pf.std_error > 0.5 * std::abs(pf.fitted)) add("poorly determined (error > 50%)");
        }
        pf.note = n;
    }
    return res;
}

}  // namespace rtc
