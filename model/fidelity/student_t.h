// SPDX-License-Identifier: Apache-2.0
// Student's t distribution: the CDF (regularized incomplete beta, continued fraction)
// and its quantile by bisection, for the sampled level's confidence intervals.
#pragma once

namespace rastsim::fidelity {

// P(T <= t) for T ~ Student t with `df` > 0 degrees of freedom (df need not be integer).
double student_t_cdf(double t, double df);
// The q-quantile (0 < q < 1) of Student t with `df` degrees of freedom.
double student_t_quantile(double q, double df);

}  // namespace rastsim::fidelity
