/* A tiny test harness: CHECK macros that count failures, and a main() helper.
 * Each test program is `int main(void) { ...; return check_report(); }`. */
#ifndef IL_TESTS_CHECK_H
#define IL_TESTS_CHECK_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>

#include "core/lsan_suppressions.h"

static int check_failures = 0;
static int check_count = 0;

#define CHECK(cond)                                                                      \
    do {                                                                                 \
        check_count++;                                                                   \
        if (!(cond)) {                                                                   \
            check_failures++;                                                            \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond);     \
        }                                                                                \
    } while (0)

/* |a-b| <= tol */
#define CHECK_NEAR(a, b, tol)                                                            \
    do {                                                                                 \
        double check_a_ = (double)(a), check_b_ = (double)(b), check_t_ = (double)(tol);  \
        check_count++;                                                                   \
        if (!(fabs(check_a_ - check_b_) <= check_t_)) {                                  \
            check_failures++;                                                            \
            fprintf(stderr, "%s:%d: CHECK_NEAR failed: %s = %.9g, %s = %.9g, tol %.3g\n", \
                    __FILE__, __LINE__, #a, check_a_, #b, check_b_, check_t_);           \
        }                                                                                \
    } while (0)

/* |a-b| <= rel * |b| */
#define CHECK_REL(a, b, rel)                                                             \
    do {                                                                                 \
        double check_a_ = (double)(a), check_b_ = (double)(b), check_r_ = (double)(rel);  \
        check_count++;                                                                   \
        if (!(fabs(check_a_ - check_b_) <= check_r_ * fabs(check_b_))) {                 \
            check_failures++;                                                            \
            fprintf(stderr, "%s:%d: CHECK_REL failed: %s = %.9g, %s = %.9g, rel %.3g\n",  \
                    __FILE__, __LINE__, #a, check_a_, #b, check_b_, check_r_);           \
        }                                                                                \
    } while (0)

/* Asserts a call returned IL_OK and prints its message otherwise. */
#define CHECK_OK(call, errp)                                                             \
    do {                                                                                 \
        check_count++;                                                                   \
        if ((call) != IL_OK) {                                                           \
            check_failures++;                                                            \
            fprintf(stderr, "%s:%d: %s failed: %s\n", __FILE__, __LINE__, #call,          \
                    (errp)->message);                                                    \
        }                                                                                \
    } while (0)

static inline int check_report(void)
{
    printf("%d checks, %d failed\n", check_count, check_failures);
    return check_failures ? 1 : 0;
}

/* A scratch directory for this test program (created on demand). */
static inline const char *check_tmp_dir(void)
{
    mkdir(IL_TEST_TMP, 0755);
    return IL_TEST_TMP;
}

#endif
