/* Pearson's chi-square goodness-of-fit test of a sample histogram against the
 * expected counts, in the style of Mitsuba's ChiSquareTest (Jakob et al.,
 * mitsuba/python/chi2.py): cells expecting fewer than CHI2_MIN_EXPECTED samples
 * are pooled, a cell with samples but no expectation fails outright, and the
 * statistic is compared with the chi-square distribution's upper tail.
 * Shared by test_sampling.c and test_bsdf.c (header only, all static). */
#ifndef IL_TESTS_CHI2_H
#define IL_TESTS_CHI2_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define CHI2_MIN_EXPECTED 5.0

/* Regularised upper incomplete gamma Q(a, x) = Gamma(a, x) / Gamma(a):
 * power series of P for x < a + 1, Lentz continued fraction for Q otherwise
 * (Abramowitz & Stegun 6.5.29 and 6.5.31). */
static double chi2_gamma_q(double a, double x)
{
    if (x <= 0.0)
        return 1.0;
    double log_prefix = a * log(x) - x - lgamma(a);
    if (x < a + 1.0) {
        double term = 1.0 / a, sum = term;
        for (int k = 1; k < 100000; k++) {
            term *= x / (a + k);
            sum += term;
            if (fabs(term) < fabs(sum) * 1e-15)
                break;
        }
        return 1.0 - sum * exp(log_prefix);
    }
    const double tiny = 1e-300;
    double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int k = 1; k < 100000; k++) {
        double an = -k * (k - a);
        b += 2.0;
        d = an * d + b;
        if (fabs(d) < tiny) d = tiny;
        c = b + an / c;
        if (fabs(c) < tiny) c = tiny;
        d = 1.0 / d;
        double delta = d * c;
        h *= delta;
        if (fabs(delta - 1.0) < 1e-15)
            break;
    }
    return exp(log_prefix) * h;
}

static int chi2_cmp_expected(const void *a, const void *b)
{
    const double *x = a, *y = b;
    return (x[0] > y[0]) - (x[0] < y[0]);
}

/* Returns the p-value of observing counts `obs` given expected counts `expd`
 * (n cells).  Returns -1 when a cell has observations but zero expectation
 * (a certain failure). */
static double chi2_pvalue(const double *obs, const double *expd, int n, const char *label)
{
    double *pairs = malloc(sizeof(double) * 2 * (size_t)n);
    for (int i = 0; i < n; i++) {
        pairs[2 * i] = expd[i];
        pairs[2 * i + 1] = obs[i];
        if (expd[i] <= 0.0 && obs[i] > 0.0) {
            fprintf(stderr, "%s: cell %d has %g samples but expects none\n", label, i, obs[i]);
            free(pairs);
            return -1.0;
        }
    }
    qsort(pairs, (size_t)n, 2 * sizeof(double), chi2_cmp_expected);
    double stat = 0.0, pool_e = 0.0, pool_o = 0.0;
    int cells = 0;
    for (int i = 0; i < n; i++) {
        double e = pairs[2 * i], o = pairs[2 * i + 1];
        if (e <= 0.0)
            continue;
        if (e < CHI2_MIN_EXPECTED || pool_e > 0.0) {
            /* Pool small cells (smallest first) until the pool is big enough. */
            pool_e += e;
            pool_o += o;
            if (pool_e >= CHI2_MIN_EXPECTED) {
                stat += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
                cells++;
                pool_e = pool_o = 0.0;
            }
            continue;
        }
        stat += (o - e) * (o - e) / e;
        cells++;
    }
    if (pool_e > 0.0) {
        stat += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
        cells++;
    }
    free(pairs);
    int dof = cells - 1;
    if (dof < 1)
        return 1.0;
    double p = chi2_gamma_q(0.5 * dof, 0.5 * stat);
    if (getenv("IL_CHI2_VERBOSE"))
        printf("%s: chi2 = %.1f, dof = %d, p = %.4f\n", label, stat, dof, p);
    return p;
}

/* Sidak-corrected per-test significance for a family of `tests` tests at
 * overall level `alpha`. */
static double chi2_significance(double alpha, int tests)
{
    return 1.0 - pow(1.0 - alpha, 1.0 / tests);
}

#endif
